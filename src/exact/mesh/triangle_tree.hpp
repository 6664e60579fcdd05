// Bounding-box trees over a mesh's triangles and the floating-point bounds that cull pairs of
// triangles before exact arithmetic (private to src/exact/mesh; no CGAL here).
//
// Every bound that prunes is a proven lower bound of a squared distance: the rounding of each
// operation is accounted for (u = 2^-53, the unit roundoff of double), so a pair is dropped only
// when its exact squared distance certainly exceeds the exact value already in hand. The
// approximate closest points only order the work and choose the bound's direction.
#pragma once

#include <array>
#include <cstdint>
#include <queue>
#include <span>
#include <utility>
#include <vector>

#include "gjklab/exact/mesh_truth.hpp"

namespace gjklab::exact::mesh {

/// A closed axis-aligned box; its corners are exact (minima and maxima of the vertices).
struct Box {
  Vec3 lo, hi;
};

/// The closed boxes share a point (exact comparisons).
bool boxes_overlap(const Box& a, const Box& b);
/// A lower bound of the squared distance between the boxes (0 when they overlap or nearly do).
double box_gap_squared_lower(const Box& a, const Box& b);

using Triangle = std::array<Vec3, 3>;

/// Closest points of two triangles in double arithmetic (not proven; for disjoint triangles,
/// where the minimum is attained at a vertex and a triangle or at two edges).
struct ApproxClosest {
  Vec3 on_a, on_b;
  double distance_squared = 0;
};
ApproxClosest approximate_closest(const Triangle& a, const Triangle& b);

/// A lower bound of the squared distance between the triangles from the direction n (pointing
/// from A towards B): the gap between their extents along n, divided by |n|, squared. 0 when n
/// is zero or the extents overlap.
double direction_gap_squared_lower(const Triangle& a, const Triangle& b, const Vec3& n);

/// A tree of boxes over a mesh's triangles: each node's box holds its triangles; a leaf holds at
/// most kLeafSize of them. Built by splitting the longest axis at the median centroid.
class TriangleTree {
 public:
  static constexpr std::uint32_t kLeafSize = 4;
  struct Node {
    Box box;
    std::uint32_t first = 0, count = 0;  ///< leaf: faces order()[first, first + count)
    std::uint32_t left = 0, right = 0;   ///< inner node: children (count == 0)
    bool leaf() const { return count > 0; }
  };

  explicit TriangleTree(const MeshView& mesh);
  std::span<const Node> nodes() const { return nodes_; }  ///< root first
  std::span<const std::uint32_t> order() const { return order_; }
  const Box& face_box(std::uint32_t face) const { return face_boxes_[face]; }
  Triangle triangle(std::uint32_t face) const;

 private:
  std::uint32_t build(std::uint32_t first, std::uint32_t count);

  MeshView mesh_;
  std::vector<Box> face_boxes_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

/// Whether a pair of nodes is refined by splitting A's (else B's): the inner node, or of two
/// inner nodes the larger box, so that the two trees descend in step.
bool split_a(const TriangleTree::Node& a, const TriangleTree::Node& b);

/// Calls visit(fa, fb) for the face pairs whose boxes overlap, until it returns true; returns
/// whether it did.
template <class Visit>
bool any_overlapping_faces(const TriangleTree& a, const TriangleTree& b, Visit&& visit) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [ia, ib] = stack.back();
    stack.pop_back();
    const auto &na = a.nodes()[ia], &nb = b.nodes()[ib];
    if (!boxes_overlap(na.box, nb.box)) continue;
    if (na.leaf() && nb.leaf()) {
      for (std::uint32_t fa : a.order().subspan(na.first, na.count))
        for (std::uint32_t fb : b.order().subspan(nb.first, nb.count))
          if (boxes_overlap(a.face_box(fa), b.face_box(fb)) && visit(fa, fb)) return true;
    } else if (split_a(na, nb)) {
      stack.push_back({na.left, ib});
      stack.push_back({na.right, ib});
    } else {
      stack.push_back({ia, nb.left});
      stack.push_back({ia, nb.right});
    }
  }
  return false;
}

/// Calls visit(fa, fb) on the face pairs whose boxes' bound does not exceed bound() (a squared
/// upper bound that visit may lower), nearest node pairs first.
template <class Bound, class Visit>
void near_faces(const TriangleTree& a, const TriangleTree& b, Bound&& bound, Visit&& visit) {
  struct Item {
    double gap;
    std::uint32_t ia, ib;
    bool operator>(const Item& o) const { return gap > o.gap; }
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  queue.push({box_gap_squared_lower(a.nodes()[0].box, b.nodes()[0].box), 0, 0});
  while (!queue.empty() && !(queue.top().gap > bound())) {
    const Item item = queue.top();
    queue.pop();
    const auto &na = a.nodes()[item.ia], &nb = b.nodes()[item.ib];
    auto push = [&](std::uint32_t ia, std::uint32_t ib) {
      const double gap = box_gap_squared_lower(a.nodes()[ia].box, b.nodes()[ib].box);
      if (!(gap > bound())) queue.push({gap, ia, ib});
    };
    if (na.leaf() && nb.leaf()) {
      for (std::uint32_t fa : a.order().subspan(na.first, na.count))
        for (std::uint32_t fb : b.order().subspan(nb.first, nb.count))
          if (!(box_gap_squared_lower(a.face_box(fa), b.face_box(fb)) > bound())) visit(fa, fb);
    } else if (split_a(na, nb)) {
      push(na.left, item.ib);
      push(na.right, item.ib);
    } else {
      push(item.ia, nb.left);
      push(item.ia, nb.right);
    }
  }
}

}  // namespace gjklab::exact::mesh
