// FHR core — strong index types (design.md §2): a VertexId cannot be passed where a FaceId is meant.
#pragma once

#include <compare>
#include <cstdint>
#include <functional>
#include <limits>

namespace fhr {

/// An index into one kind of mesh element. Default-constructed ids are invalid.
template <class Tag>
class Id {
public:
    using Index = std::uint32_t;
    static constexpr Index invalid_index = std::numeric_limits<Index>::max();

    constexpr Id() = default;
    constexpr explicit Id(Index i) : i_(i) {}
    constexpr Index idx() const { return i_; }
    constexpr bool valid() const { return i_ != invalid_index; }
    constexpr auto operator<=>(const Id&) const = default;

private:
    Index i_ = invalid_index;
};

using VertexId = Id<struct VertexTag>;
using HalfedgeId = Id<struct HalfedgeTag>;
using EdgeId = Id<struct EdgeTag>;
using FaceId = Id<struct FaceTag>;

/// `for (VertexId v : IdRange<VertexId>(n))` visits ids 0..n-1 in order.
template <class IdT>
class IdRange {
public:
    class iterator {
    public:
        constexpr explicit iterator(typename IdT::Index i) : i_(i) {}
        constexpr IdT operator*() const { return IdT(i_); }
        constexpr iterator& operator++() { ++i_; return *this; }
        constexpr bool operator==(const iterator&) const = default;
    private:
        typename IdT::Index i_;
    };
    constexpr explicit IdRange(std::size_t n) : n_(static_cast<typename IdT::Index>(n)) {}
    constexpr iterator begin() const { return iterator(0); }
    constexpr iterator end() const { return iterator(n_); }
private:
    typename IdT::Index n_;
};

}  // namespace fhr

template <class Tag>
struct std::hash<fhr::Id<Tag>> {
    std::size_t operator()(fhr::Id<Tag> id) const noexcept { return std::hash<std::uint32_t>()(id.idx()); }
};
