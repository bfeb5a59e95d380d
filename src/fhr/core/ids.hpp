// FHR core — strong index types: a VertexId cannot be passed where a FaceId is meant, and
// per-element data (IdVector) is indexed by its own id type only. Where the elements of several
// meshes meet — T′ of §3 holding, per element, the domain D's and the input T's elements
// (partition::Network), the final T′ with its patch per face (pipeline::Parameterization) — the
// other meshes' elements have id types of their own (DFaceId, TFaceId, …): a face of D cannot be
// taken for a face of T′ or of T without saying so (an explicit conversion).
#pragma once

#include <compare>
#include <cstdint>
#include <functional>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace fhr {

/// The mesh an id names an element of: any mesh (the ids a TriMesh hands out), or, where meshes
/// meet, the input surface T, the domain D or the final T′ (T′ of §3 with its patches' dividing
/// edges split: the faces of the `fhr-param 1` file, in its order).
struct AnyMesh;
struct SurfaceT;
struct DomainD;
struct RefinedT;

/// An index into one kind of element of one kind of mesh. Default-constructed ids are invalid.
template <class Tag, class Mesh = AnyMesh>
class Id {
public:
    using Index = std::uint32_t;
    static constexpr Index invalid_index = std::numeric_limits<Index>::max();

    constexpr Id() = default;
    constexpr explicit Id(Index i) : i_(i) {}
    /// The same element under another mesh's id type (a TriMesh's own id for T's or D's, or back):
    /// only explicitly, where the code says which mesh it means.
    template <class Other>
    requires(!std::is_same_v<Other, Mesh>) constexpr explicit Id(Id<Tag, Other> other) : i_(other.idx()) {}
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

/// Elements of the input surface T where they meet elements of other meshes.
using TVertexId = Id<VertexTag, SurfaceT>;
using TEdgeId = Id<EdgeTag, SurfaceT>;
using TFaceId = Id<FaceTag, SurfaceT>;
/// Elements of the domain D where they meet elements of other meshes.
using DVertexId = Id<VertexTag, DomainD>;
using DHalfedgeId = Id<HalfedgeTag, DomainD>;
using DEdgeId = Id<EdgeTag, DomainD>;
using DFaceId = Id<FaceTag, DomainD>;
/// Faces of the final T′.
using RefinedFaceId = Id<FaceTag, RefinedT>;

/// `for (VertexId v : IdRange<VertexId>(n))` visits ids 0..n-1 in order.
template <class IdT>
class IdRange {
public:
    class iterator {
    public:
        constexpr explicit iterator(typename IdT::Index i) : i_(i) {}
        constexpr IdT operator*() const { return IdT(i_); }
        constexpr iterator& operator++() {
            ++i_;
            return *this;
        }
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

/// Per-element data: a vector that only its id type indexes, so that a FaceId cannot index
/// per-vertex data (a compile error, not a silent mix-up). Iterates over its values like a vector.
template <class IdT, class T>
class IdVector {
public:
    IdVector() = default;
    explicit IdVector(std::size_t n, const T& value = T()) : data_(n, value) {}
    /// One value per element of IdT's kind of `mesh` (element_count, found with the mesh type).
    template <class Mesh>
    requires requires(const Mesh& m) { element_count(m, IdT()); }
    IdVector(const Mesh& mesh, const T& value) : data_(element_count(mesh, IdT()), value) {}
    /// Whether this holds exactly one value per element of IdT's kind of `mesh`.
    template <class Mesh>
    bool fits(const Mesh& mesh) const {
        return data_.size() == element_count(mesh, IdT());
    }
    /// Adopts `values` as the data of ids 0, 1, … in order.
    explicit IdVector(std::vector<T> values) : data_(std::move(values)) {}
    T& operator[](IdT id) { return data_[id.idx()]; }
    const T& operator[](IdT id) const { return data_[id.idx()]; }
    /// Bounds-checked: \throws std::out_of_range.
    const T& at(IdT id) const { return data_.at(id.idx()); }
    std::size_t size() const { return data_.size(); }
    bool empty() const { return data_.empty(); }
    void resize(std::size_t n, const T& value = T()) { data_.resize(n, value); }
    void assign(std::size_t n, const T& value) { data_.assign(n, value); }
    void reserve(std::size_t n) { data_.reserve(n); }
    void clear() { data_.clear(); }
    /// Appends the data of the next id, size() before the call.
    void push_back(const T& value) { data_.push_back(value); }
    void push_back(T&& value) { data_.push_back(std::move(value)); }
    template <class... Args>
    T& emplace_back(Args&&... args) {
        return data_.emplace_back(std::forward<Args>(args)...);
    }
    T& back() { return data_.back(); }
    const T& back() const { return data_.back(); }
    IdRange<IdT> ids() const { return IdRange<IdT>(data_.size()); }
    /// All values in id order, for bulk use (writers, spans): no id checks there.
    const std::vector<T>& values() const { return data_; }
    auto begin() { return data_.begin(); }
    auto end() { return data_.end(); }
    auto begin() const { return data_.begin(); }
    auto end() const { return data_.end(); }
    bool operator==(const IdVector&) const = default;

private:
    std::vector<T> data_;
};

template <class T>
using VertexData = IdVector<VertexId, T>;
template <class T>
using HalfedgeData = IdVector<HalfedgeId, T>;
template <class T>
using EdgeData = IdVector<EdgeId, T>;
template <class T>
using FaceData = IdVector<FaceId, T>;

}  // namespace fhr

template <class Tag, class Mesh>
struct std::hash<fhr::Id<Tag, Mesh>> {
    std::size_t operator()(fhr::Id<Tag, Mesh> id) const noexcept { return std::hash<std::uint32_t>()(id.idx()); }
};
