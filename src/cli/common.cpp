// FHR cli — shared argument parsing, mesh loading and saving (see common.hpp).
#include "cli/common.hpp"

#include <charconv>
#include <cstdio>

#include <fhr/core/errors.hpp>
#include <fhr/io/read.hpp>
#include <fhr/io/write.hpp>

namespace fhr::cli {

void usage_error(const std::string& what) { throw InvalidInput(what + " (see `fhr help`)"); }

int exit_code_of(const std::exception& e) {
    if (dynamic_cast<const InvalidInput*>(&e)) return 2;
    if (dynamic_cast<const PartitionFailure*>(&e)) return 3;
    if (dynamic_cast<const NumericalFailure*>(&e)) return 4;
    return 70;
}

Args::Args(const std::vector<std::string>& argv, const std::vector<std::string>& flags,
           const std::vector<std::string>& valued) {
    auto listed = [](const std::vector<std::string>& names, const std::string& n) {
        for (const auto& x : names)
            if (x == n) return true;
        return false;
    };
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.size() > 2 && a.compare(0, 2, "--") == 0) {
            const std::string name = a.substr(2);
            if (listed(flags, name)) {
                flags_[name] = true;
            } else if (listed(valued, name)) {
                if (i + 1 >= argv.size()) usage_error("option --" + name + " needs a value");
                if (values_.count(name)) usage_error("option --" + name + " is given twice");
                values_[name] = argv[++i];
            } else {
                usage_error("unknown option " + a);
            }
        } else {
            positional_.push_back(a);
        }
    }
}

const std::string& Args::single_positional(const std::string& what) const {
    if (positional_.size() != 1)
        usage_error("expected exactly one " + what + ", got " + std::to_string(positional_.size()) + " arguments");
    return positional_[0];
}

std::optional<std::string> Args::get(const std::string& name) const {
    const auto it = values_.find(name);
    if (it == values_.end()) return std::nullopt;
    return it->second;
}

const std::string& Args::require(const std::string& name) const {
    const auto it = values_.find(name);
    if (it == values_.end()) usage_error("option --" + name + " is required");
    return it->second;
}

long long Args::integer(const std::string& name, long long fallback, long long min, long long max) const {
    const auto v = get(name);
    if (!v) return fallback;
    long long x = 0;
    const auto r = std::from_chars(v->data(), v->data() + v->size(), x);
    if (r.ec != std::errc() || r.ptr != v->data() + v->size())
        usage_error("option --" + name + " needs an integer, got '" + *v + "'");
    if (x < min || x > max)
        usage_error("option --" + name + " must be in [" + std::to_string(min) + ", " + std::to_string(max) +
                    "], got " + *v);
    return x;
}

double Args::real(const std::string& name, double fallback, double min, double max) const {
    const auto v = get(name);
    if (!v) return fallback;
    double x = 0;
    const auto r = std::from_chars(v->data(), v->data() + v->size(), x);
    if (r.ec != std::errc() || r.ptr != v->data() + v->size() || !(x >= min && x <= max))
        usage_error("option --" + name + " needs a number in [" + std::to_string(min) + ", " + std::to_string(max) +
                    "], got '" + *v + "'");
    return x;
}

void print_warnings(const BuildLog& log) {
    for (const auto& w : log.warnings) std::fprintf(stderr, "fhr: warning: %s\n", w.c_str());
}

TriMesh load_mesh(const std::string& path, const BuildOptions& options) {
    BuildLog log;
    TriMesh mesh = io::read_mesh(path, options, &log);
    print_warnings(log);
    return mesh;
}

void save_mesh(const std::string& path, const TriMesh& mesh) {
    io::write_mesh(path, mesh.positions(), mesh.triangles());
}

}  // namespace fhr::cli
