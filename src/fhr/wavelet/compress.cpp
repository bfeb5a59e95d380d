// FHR §6 (Fig. 9) — keeping the largest wavelet coefficients (see compress.hpp).
#include <fhr/core/detail/contract.hpp>
#include <fhr/wavelet/detail/compress.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <fhr/core/errors.hpp>

namespace fhr::wavelet {

std::size_t kept_count(std::size_t total, double percent) {
    if (!(percent >= 0 && percent <= 100))
        throw InvalidInput("compression: the kept percentage " + std::to_string(percent) + " is not in [0, 100]");
    // percent·total is exact for total < 2^53 / 100 and an integer percent; 100·total/100 = total.
    return std::min(total, static_cast<std::size_t>(std::floor(percent * static_cast<double>(total) / 100.0)));
}

std::vector<double> coefficient_magnitudes(const FilterBank& bank, const Decomposition& d) {
    std::vector<double> key;
    key.reserve(d.coefficient_count());
    for (std::size_t j = 0; j < d.detail.size(); ++j) {
        const LevelFilter& L = bank.level(static_cast<int>(j) + 1);
        for (std::size_t k = 0; k < d.detail[j].size(); ++k) key.push_back(d.detail[j][k].norm() * L.norm[k]);
    }
    return key;
}

Decomposition keep_largest(const FilterBank& bank, const Decomposition& d, std::size_t count) {
    FHR_DCHECK(count <= d.coefficient_count());
    const std::vector<double> key = coefficient_magnitudes(bank, d);
    std::vector<std::size_t> order(key.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    // The flat index runs level by level, so "ties by level then index" is "ties by flat index".
    auto larger = [&](std::size_t a, std::size_t b) { return key[a] > key[b] || (key[a] == key[b] && a < b); };
    count = std::min(count, order.size());
    std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(), larger);
    std::vector<char> keep(key.size(), 0);
    for (std::size_t i = 0; i < count; ++i) keep[order[i]] = 1;
    Decomposition out = d;
    std::size_t flat = 0;
    for (auto& level : out.detail)
        for (Vec3& c : level)
            if (!keep[flat++]) c.setZero();
    return out;
}

}  // namespace fhr::wavelet
