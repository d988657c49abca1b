// Uniform midpoint refinement (Aulisa & Capodaglio §6.2: "the mesh was refined J times", J = 1..4
// for Test A; each refinement quarters every QUAD9). Each Q4/Q9/T3/T6 becomes 4 children, each
// Hex8 8; the new nodes are placed by the parent's isoparametric map x(xi) = sum_i x_i N_i(xi), so
// children of a curved Q9 or T6 stay on its geometry (the child's map is the restriction of the
// parent's).
//
// Numbering: the parent's nodes keep their ids 0..n-1; new nodes follow in order of first
// appearance (element, child, local node). A new node shared by neighbours (on an edge or face) is
// merged through a topological key, the parent-corner weights of the point (the values of the
// element's linear version at its reference position: exact multiples of 1/64), which neighbours
// compute identically whatever their orientation; no coordinate tolerance is involved. Child k of
// parent e is element e * children + k. Node sets, element sets and boundary faces carry over.
#pragma once

#include "matpoint/mesh/mesh.hpp"

namespace matpoint::mesh {

/// The mesh refined `levels` times (levels = 0 returns a copy).
template <int D>
Mesh<D> refine(const Mesh<D>& mesh, int levels);

extern template Mesh<2> refine(const Mesh<2>&, int);
extern template Mesh<3> refine(const Mesh<3>&, int);

}  // namespace matpoint::mesh
