#include "compile/bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <limits>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <glm/common.hpp>

namespace spectrace {
namespace {

constexpr uint32_t kMaxLeaf = device::kBvhMaxLeafPrimitives;
constexpr uint32_t kMaxDepth = device::kBvhMaxDepth;
constexpr int kBins = 16;
// The cost of one traversal step relative to one primitive test, by
// measurement, not pbrt-v4's 0.5: a step reads a node, most often a cache
// miss in a large mesh, and a leaf's primitives lie side by side. On the
// ray ceiling's million-triangle mesh (the four-wide walk, the CPU, 2
// threads), 0.5 gave 1.11 Mray/s and 86 bytes a triangle, 1 gave 1.21 and
// 81, 2 gave 1.57 and 68, 4 gave 1.57 and 60, 8 gave 1.58 and 59 (leaves
// fill up to kMaxLeaf).
constexpr double kTraversalCost = 4.0;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Box {
  glm::dvec3 lo{kInf}, hi{-kInf};
  void extend(const glm::dvec3& lo2, const glm::dvec3& hi2) {
    lo = glm::min(lo, lo2);
    hi = glm::max(hi, hi2);
  }
  void extend(const Box& b) { extend(b.lo, b.hi); }
  // Half the surface area; 0 for an empty or flat-to-a-line box.
  double halfArea() const {
    const glm::dvec3 e = glm::max(hi - lo, glm::dvec3(0.0));
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

// The float at or below d (at or above for roundUp): the nodes' float
// bounds must contain the double bounds. Out-of-range values are clamped
// by hand, since converting them to float is undefined behaviour.
float roundDown(double d) {
  constexpr float kMax = std::numeric_limits<float>::max();
  if (d > kMax) return kMax;
  if (d < -double(kMax)) return -std::numeric_limits<float>::infinity();
  float f = static_cast<float>(d);
  if (double(f) > d) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

float roundUp(double d) {
  constexpr float kMax = std::numeric_limits<float>::max();
  if (d < -double(kMax)) return -kMax;
  if (d > kMax) return std::numeric_limits<float>::infinity();
  float f = static_cast<float>(d);
  if (double(f) < d) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// Levels a subtree of n primitives needs when built by median splits alone:
// what must still fit under the depth limit whatever SAH chooses.
uint32_t levelsForMedianSplits(uint32_t n) {
  uint32_t levels = 1;
  for (; n > kMaxLeaf; n = (n + 1) / 2) ++levels;
  return levels;
}

// A primitive as the builder moves it around: partitioning these in place
// reads memory in order, where partitioning indices would jump around the
// inputs.
struct Item {
  glm::dvec3 lo, hi;
  uint32_t index;
  glm::dvec3 centroid() const { return 0.5 * lo + 0.5 * hi; }  // lo + hi could overflow
};

// Two doubles in one register (GCC's and Clang's vector types; SSE2 on
// x86-64). The builder's passes extend boxes by every item they read, and
// glm's dvec3 does that one component at a time.
typedef double Double2 __attribute__((vector_size(16)));
// glm::min(acc, x) and glm::max(acc, x) on each lane, the same bits
// (GCC makes these one minpd and one maxpd).
inline Double2 lesser(Double2 acc, Double2 x) { return x < acc ? x : acc; }
inline Double2 greater(Double2 acc, Double2 x) { return acc < x ? x : acc; }

// A Box as x and y in a pair, z alone.
struct PackedBox {
  Double2 loXY{kInf, kInf}, hiXY{-kInf, -kInf};
  double loZ = kInf, hiZ = -kInf;
  void extend(Double2 lxy, double lz, Double2 hxy, double hz) {
    loXY = lesser(loXY, lxy);
    hiXY = greater(hiXY, hxy);
    loZ = glm::min(loZ, lz);
    hiZ = glm::max(hiZ, hz);
  }
  Box unpacked() const { return Box{{loXY[0], loXY[1], loZ}, {hiXY[0], hiXY[1], hiZ}}; }
};

// An item's bounds and centroid, packed.
struct PackedItem {
  Double2 loXY, hiXY, centroidXY;
  double loZ, hiZ, centroidZ;
  PackedItem() = default;
  explicit PackedItem(const Item& it)
      : loXY{it.lo.x, it.lo.y}, hiXY{it.hi.x, it.hi.y}, loZ(it.lo.z), hiZ(it.hi.z) {
    // Item::centroid's operations, lane by lane.
    centroidXY = 0.5 * loXY + 0.5 * hiXY;
    centroidZ = 0.5 * loZ + 0.5 * hiZ;
  }
  double centroid(int axis) const { return axis < 2 ? centroidXY[axis] : centroidZ; }
};

// The bounds of some items, and of their centroids.
struct ItemBounds {
  PackedBox box, centroids;
  void add(const Item& item) { add(PackedItem(item)); }
  void add(const PackedItem& it) {
    box.extend(it.loXY, it.loZ, it.hiXY, it.hiZ);
    centroids.extend(it.centroidXY, it.centroidZ, it.centroidXY, it.centroidZ);
  }
};

// Subtrees of at least this many primitives may be built on a thread of
// their own: below it, a thread's start costs more than the work.
constexpr uint32_t kMinForkedPrimitives = 1u << 15;

// A subtree's nodes, depth first, its root at 0; interior `next` indices
// count from that root, leaf `next` indices are final (item places).
struct Subtree {
  std::vector<BinaryBvhNode> nodes;
  uint32_t depth = 0;  // deepest level reached, counted from the tree's root

  // Appends `sub` after this subtree's nodes, moving its interior indices.
  void append(const Subtree& sub) {
    const uint32_t offset = uint32_t(nodes.size());
    nodes.reserve(nodes.size() + sub.nodes.size());
    for (BinaryBvhNode node : sub.nodes) {
      if (node.primitiveCount() == 0) node.next += offset;
      nodes.push_back(node);
    }
    depth = std::max(depth, sub.depth);
  }
};

class Builder {
 public:
  Builder(std::span<const PrimitiveBounds> bounds, unsigned threads, BuiltBvh& out) : out_(out) {
    items_.resize(bounds.size());
    for (size_t i = 0; i < bounds.size(); ++i) items_[i] = Item{bounds[i].lo, bounds[i].hi, uint32_t(i)};
    // Forks happen on the top levels; each doubles the tasks at work.
    while ((1u << forkLevels_) < threads && forkLevels_ < 8) ++forkLevels_;
  }

  // Builds the tree, then reads `order` off the items' final places.
  void buildAll() {
    Subtree tree;
    const uint32_t n = uint32_t(items_.size());
    build(0, n, 1, tree, boundsOf(0, n));
    out_.nodes = std::move(tree.nodes);
    out_.depth = tree.depth;
    out_.order.resize(items_.size());
    for (size_t k = 0; k < items_.size(); ++k) out_.order[k] = items_[k].index;
  }

 private:
  struct Split {
    int axis = -1;  // -1: none found
    int bin = 0;    // the left child takes bins [0, bin]
    uint32_t leftCount = 0;
    double cost = kInf;  // in units of one primitive test
  };

  // Maps centroids to SAH bins along each axis. Halved coordinates keep
  // extents of up to twice DBL_MAX finite; a reciprocal that overflows
  // (denormal extents) gives inf or NaN, which the clamp sends to the end
  // bins. Binning and partition both call it, so they agree.
  struct Binning {
    glm::dvec3 halfLo, binsPerHalfUnit;
    explicit Binning(const Box& centroidBox)
        : halfLo(0.5 * centroidBox.lo), binsPerHalfUnit(double(kBins) / (0.5 * centroidBox.hi - halfLo)) {}
    // The bin of centroid coordinate c on `axis`.
    int operator()(double c, int axis) const {
      const double t = (0.5 * c - halfLo[axis]) * binsPerHalfUnit[axis];
      return t >= double(kBins - 1) ? kBins - 1 : (t > 0.0 ? int(t) : 0);
    }
    std::array<int, 3> operator()(const PackedItem& it) const {
      return {(*this)(it.centroidXY[0], 0), (*this)(it.centroidXY[1], 1), (*this)(it.centroidZ, 2)};
    }
  };

  // Builds the subtree of items [begin, end) whose root is at `level` (the
  // tree's root: 1), appending its nodes to `tree` depth first. Every
  // decision depends on the items alone, so the tree is the same whether
  // its right halves are built here or on other threads: they touch
  // disjoint item ranges and their nodes are appended in the same order.
  void build(uint32_t begin, uint32_t end, uint32_t level, Subtree& tree, const ItemBounds& bounds) {
    const uint32_t nodeIndex = uint32_t(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.depth = std::max(tree.depth, level);
    const uint32_t n = end - begin;

    const Box box = bounds.box.unpacked();
    const Box centroidBox = bounds.centroids.unpacked();
    BinaryBvhNode& node = tree.nodes[nodeIndex];
    node.boundsMin = glm::vec3(roundDown(box.lo.x), roundDown(box.lo.y), roundDown(box.lo.z));
    node.boundsMax = glm::vec3(roundUp(box.hi.x), roundUp(box.hi.y), roundUp(box.hi.z));

    const glm::dvec3 extent = centroidBox.hi - centroidBox.lo;
    const bool centroidsCoincide = !(extent.x > 0.0 || extent.y > 0.0 || extent.z > 0.0);
    if (n == 1 || (n <= kMaxLeaf && (centroidsCoincide || level == kMaxDepth)))
      return makeLeaf(tree.nodes[nodeIndex], begin, n);

    uint32_t mid = begin + n / 2;  // coinciding centroids: split the list in the middle
    int axis = 0;
    std::array<ItemBounds, 2> childBounds;
    bool childBoundsKnown = false;
    if (!centroidsCoincide) {
      axis = extent.y > extent[axis] ? 1 : axis;
      axis = extent.z > extent[axis] ? 2 : axis;
      const Split split = bestSahSplit(begin, end, box, centroidBox);
      if (split.axis >= 0 && n <= kMaxLeaf && !(split.cost < double(n)))
        return makeLeaf(tree.nodes[nodeIndex], begin, n);
      // A split the depth limit allows: each child must still fit with
      // median splits below it.
      const uint32_t childLevels = kMaxDepth - level;
      const auto first = items_.begin();
      if (split.axis >= 0 &&
          levelsForMedianSplits(std::max(split.leftCount, n - split.leftCount)) <= childLevels) {
        axis = split.axis;
        const Binning binOf(centroidBox);
        const auto goesLeft = [&](const PackedItem& it) { return binOf(it.centroid(axis), axis) <= split.bin; };
        mid = partitionWithBounds(begin, end, goesLeft, childBounds);
        childBoundsKnown = true;
      } else {
        // Median along the widest centroid extent: halves the count, so the
        // remaining depth always suffices.
        std::nth_element(first + begin, first + mid, first + end, [&](const Item& a, const Item& b) {
          return a.centroid()[axis] < b.centroid()[axis];
        });
      }
    }

    tree.nodes[nodeIndex].countAxis = uint32_t(axis) << 16;
    if (!childBoundsKnown) childBounds = {boundsOf(begin, mid), boundsOf(mid, end)};
    if (level <= forkLevels_ && end - mid >= kMinForkedPrimitives) {
      std::future<Subtree> right = std::async(std::launch::async, [this, mid, end, level, &childBounds] {
        Subtree sub;
        build(mid, end, level + 1, sub, childBounds[1]);
        return sub;
      });
      build(begin, mid, level + 1, tree, childBounds[0]);
      tree.nodes[nodeIndex].next = uint32_t(tree.nodes.size());
      tree.append(right.get());
      return;
    }
    build(begin, mid, level + 1, tree, childBounds[0]);
    tree.nodes[nodeIndex].next = uint32_t(tree.nodes.size());
    build(mid, end, level + 1, tree, childBounds[1]);
  }

  // The bounds of items [begin, end) and of their centroids.
  ItemBounds boundsOf(uint32_t begin, uint32_t end) const {
    ItemBounds b;
    for (uint32_t k = begin; k < end; ++k) b.add(items_[k]);
    return b;
  }

  // Hoare's partition of items [begin, end) by `left(item)`, with the
  // swaps libstdc++'s std::partition makes (so trees are the ones it
  // built), noting each side's bounds as it reads every item once: the
  // children need them, and would otherwise read their items again.
  template <typename Left>
  uint32_t partitionWithBounds(uint32_t begin, uint32_t end, Left left, std::array<ItemBounds, 2>& sides) {
    uint32_t first = begin, last = end;
    PackedItem goesRight, goesLeft;  // the pair a pass swaps
    while (true) {
      while (true) {
        if (first == last) return first;
        goesRight = PackedItem(items_[first]);
        if (!left(goesRight)) break;
        sides[0].add(goesRight);
        ++first;
      }
      --last;
      while (true) {
        if (first == last) {
          sides[1].add(goesRight);
          return first;
        }
        goesLeft = PackedItem(items_[last]);
        if (left(goesLeft)) break;
        sides[1].add(goesLeft);
        --last;
      }
      // Swapped, each is on its side for good.
      sides[1].add(goesRight);
      sides[0].add(goesLeft);
      std::swap(items_[first], items_[last]);
      ++first;
    }
  }

  // Binned SAH over every axis along which the centroids spread. No split
  // when the node's bounds have no area (the costs would be 0/0).
  Split bestSahSplit(uint32_t begin, uint32_t end, const Box& box, const Box& centroidBox) const {
    Split best;
    const double area = box.halfArea();
    if (!(area > 0.0) || !std::isfinite(area)) return best;
    std::array<std::array<PackedBox, kBins>, 3> binBoxes;
    std::array<std::array<uint32_t, kBins>, 3> binCounts{};
    const Binning binOf(centroidBox);
    std::array<bool, 3> spread{};
    for (int axis = 0; axis < 3; ++axis) spread[axis] = centroidBox.hi[axis] > centroidBox.lo[axis];
    // Every axis is binned, spread or not, so the loop has no branch; the
    // sweeps below pass over the bins of an axis that is not.
    for (uint32_t k = begin; k < end; ++k) {
      const PackedItem it(items_[k]);
      const std::array<int, 3> bins = binOf(it);
      for (int axis = 0; axis < 3; ++axis) {
        binBoxes[axis][bins[axis]].extend(it.loXY, it.loZ, it.hiXY, it.hiZ);
        ++binCounts[axis][bins[axis]];
      }
    }
    for (int axis = 0; axis < 3; ++axis) {
      if (!spread[axis]) continue;
      // Sweep from the right for the right-hand areas, then from the left.
      // Empty bins are passed over: a split just after one costs the same
      // as the split just before it, which the strict comparison keeps, and
      // small nodes (most of a tree's) leave most bins empty.
      std::array<double, kBins> rightArea{};
      std::array<uint32_t, kBins> rightCount{};
      Box right;
      double rightHalfArea = right.halfArea();
      uint32_t count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        if (binCounts[axis][b] != 0) {
          right.extend(binBoxes[axis][b].unpacked());
          count += binCounts[axis][b];
          rightHalfArea = right.halfArea();
        }
        rightArea[b] = rightHalfArea;
        rightCount[b] = count;
      }
      Box left;
      count = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        if (binCounts[axis][b] == 0) continue;
        left.extend(binBoxes[axis][b].unpacked());
        count += binCounts[axis][b];
        if (rightCount[b + 1] == 0) continue;
        const double cost = kTraversalCost + (count * left.halfArea() + rightCount[b + 1] * rightArea[b + 1]) / area;
        if (cost < best.cost) best = Split{axis, b, count, cost};
      }
    }
    return best;
  }

  static void makeLeaf(BinaryBvhNode& node, uint32_t begin, uint32_t n) {
    node.next = begin;
    node.countAxis = n;
  }

  std::vector<Item> items_;
  BuiltBvh& out_;
  uint32_t forkLevels_ = 0;  // levels whose nodes may build their right child on another thread
};

}  // namespace

void checkBvhPrimitiveCount(size_t count) {
  if (count >= device::kBvhMaxIndex)
    throw std::invalid_argument(fmt::format("BVH: {} primitives, at most {}", count, device::kBvhMaxIndex - 1));
}

BuiltBvh buildBvh(std::span<const PrimitiveBounds> bounds, unsigned threads) {
  // A tree has up to 2n - 1 binary nodes and fewer wide ones.
  checkBvhPrimitiveCount(bounds.size());
  for (size_t i = 0; i < bounds.size(); ++i) {
    const PrimitiveBounds& b = bounds[i];
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a]) || !(b.lo[a] <= b.hi[a]))
        throw std::invalid_argument(fmt::format("BVH: primitive {} has bounds [{}, {}] on axis {}", i, b.lo[a],
                                                b.hi[a], "xyz"[a]));
  }
  BuiltBvh out;
  if (bounds.empty()) return out;
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  Builder(bounds, threads, out).buildAll();
  return out;
}

}  // namespace spectrace
