#pragma once
// Private to accel: the layout of MeshAccel's wide tree in its array of 64-byte lines, shared by the builder
// (mesh_accel.cpp) and the traversal (mesh_traversal.hpp). The tree lies in the array depth first: each node, then the
// blocks of its leaf children, then its interior children's subtrees.
#include <cstddef>
#include <cstdint>

#include "tessera/accel/mesh_accel.hpp"

namespace tessera::mesh_tree {

/// One line of the tree's array.
using CacheLine = detail::MeshTreeLine;

/// A node of the wide tree: the boxes of its W children as rows lo.x, lo.y, lo.z, hi.x, hi.y, hi.z of W floats
/// (an unused child has an empty box, which no ray hits), and the children: >= 0 a node (see node_ref), < 0 a leaf
/// (see leaf_ref).
template <int W>
struct alignas(64) WideNode {
  float box[6][W];
  int32_t child[W];
};

/// Four triangles of a leaf, lane by lane: vertex 0, the edges to vertices 1 and 2, the mesh index (-1: unused lane,
/// whose zero edges make the determinant 0, so it never hits).
struct alignas(16) TriangleBlock {
  float v0[3][4], e1[3][4], e2[3][4];
  int32_t index[4];
};

constexpr int kMaxLeafBlocks = 32;  ///< blocks of 4 triangles per leaf (128 triangles)

/// A node's reference: its first line and how many lines of leaf blocks follow it (up to 15), so that fetching a node
/// can fetch its leaves with it.
inline int32_t node_ref(size_t line, int leaf_lines) { return int32_t((line << 4) | size_t(leaf_lines)); }
/// The first line of a node reference, and the lines of leaf blocks after the node.
inline size_t node_line(int32_t ref) { return size_t(uint32_t(ref) >> 4); }
inline int node_leaf_lines(int32_t ref) { return int(ref & 15); }
/// A leaf's reference: the offset of its first block in 32-byte units and its block count, packed into a negative
/// number.
inline int32_t leaf_ref(int first_unit, int blocks) { return ~((first_unit << 5) | (blocks - 1)); }
/// The first block (in 32-byte units) and the block count of a leaf reference.
inline int leaf_first_unit(int32_t ref) { return int(~uint32_t(ref) >> 5); }
inline int leaf_block_count(int32_t ref) { return int(~uint32_t(ref) & 31) + 1; }

}  // namespace tessera::mesh_tree
