// Fabrication data of a linkage: what a builder needs to make it from
// straight laths, drilled at the joint stations and pinned at scissor joints
// (docs/model.md sections 2, 3.2 and 5 for the terms used here).
//
// Rods. A rod is a full rod of the topology (LinkageTopology::rods), numbered
// as there: the `rod_id` of the VTK files, which draw one polyline per rod in
// rod order. Its arc length s runs from its start, the end at the first node
// of that polyline (the first node of its first segment in rod order), to its
// end at s = length.
//
// Cut length. The sum of the rod's rest edge lengths along the rod, with each
// terminal edge at a joint counted once: the two segments of a rod that meet
// at a joint share that edge (docs/model.md section 3.2). So the length is
// the sum of its segments' rest lengths along the centreline with the shared
// edges counted once. Either rest shape takes its rest lengths from the
// segments' initial polylines (docs/model.md section 3.2): on a straight rod
// the drawn length exactly (plus the overhangs below), on a curved one a
// little more, as its terminal edges follow the joints' tangents rather than
// the drawn chords.
//
// Stations, in increasing s, from 0 to the length: the rod's start (an End),
// every joint the rod passes through or ends at (a Joint, at the midpoint of
// its terminal edge, where the joint's vertex sits), and the rod's end (an
// End). A rod end at a free end (valence 1) is that vertex: its End carries
// the vertex. A rod that ends at a joint (valence 2 or 3) reaches half a
// terminal edge past it, as the model's terminal edge is centred on the
// joint: its End is that overhang's tip and carries no vertex (-1), and the
// Joint follows at s = l/2 (l the terminal edge's rest length).
//
// Valences. Valence 4: two rods pass through; the joint is a Joint station
// of both. Valence 3: one rod passes through, the other ends there (with the
// overhang above); the joint is a Joint station of both. Valence 2: two rod
// ends pinned together (the model never glues the two segments into one
// rod, even when collinear); the joint is a Joint station near an end of
// each. So every joint is a station of exactly two distinct rods, its A and
// B (build_topology refuses a joint with one rod or more than two).
//
// Closed rods (a chain of segments that returns to its first joint, possible
// on curved designs): the shared terminal edge of the closing joint is
// counted once, and the lath is cut at its start, half an edge before the
// closing joint: both Ends carry no vertex and coincide in space; the joint
// is a Joint station once, at s = l/2.
//
// Family. A joint labels its two rods A and B so that (t_A x t_B) . n > 0
// (linkage/topology.hpp). The topology propagates rod directions so that a
// rod usually carries one label at all its joints, but the labels along a rod
// can disagree: where a curved rod crosses the same rod twice, at joints
// whose rods are nearly collinear (they take no part in the propagation), and
// between parts of the linkage that only such joints connect. A rod's family
// is therefore decided by vote: the label it carries at most of its regular
// (not nearly collinear) joints; on a tie (or without regular joints), at
// most of all its joints; on a tie again, its label at its first joint in rod
// order; a rod without joints is of family A. The joints where the rod
// carries the other label are listed with it (other_label_vertices).
//
// Cross-section: that of the rod's first segment in rod order (the
// configuration sets materials per full rod, so all its segments agree).
//
// Opening angles (radians, in (0, pi)): angle(t_A, t_B) of the input graph
// (the topology's, from the drawn geometry) and of the current state
// (Joint::opening_angle).
#pragma once

#include <array>
#include <vector>

#include "linkage/rod_linkage.hpp"
#include "rod/material.hpp"

namespace xshell {

enum class RodFamily { A, B };

enum class StationKind {
  End,    // a rod end
  Joint,  // a joint the rod passes through or ends at
};

struct RodStation {
  StationKind kind = StationKind::End;
  // The OBJ vertex (0-based, input order) at this station: a joint's vertex,
  // a free end's vertex; -1 for an End that is no vertex (an overhang past a
  // joint where the rod ends, the cut of a closed rod).
  int vertex = -1;
  int joint = -1;  // Joint: the joint's index (vertex order); End: -1
  double s = 0.0;  // rest arc length from the rod's start; length unit
};

struct FabricationRod {
  int rod = -1;  // topology index, the rod_id of the VTK files
  RodFamily family = RodFamily::A;
  bool closed = false;  // the rod returns to its first joint (see above)
  double length = 0.0;  // cut (rest) length; length unit
  CrossSection section;
  std::vector<RodStation> stations;  // strictly increasing s, from 0 to length
  // Joints (their vertices, in rod order) where the rod carries the label of
  // the other family; usually none.
  std::vector<int> other_label_vertices;
};

struct FabricationJoint {
  int joint = -1;   // index (vertex order)
  int vertex = -1;  // OBJ vertex
  int valence = 0;  // 2, 3 or 4
  // Rods A and B at this joint (labels of linkage/topology.hpp), and the
  // joint's station s on each.
  std::array<int, 2> rod = {-1, -1};
  std::array<double, 2> s = {0.0, 0.0};
  double angle_input = 0.0;  // opening angle in the input, radians
  double angle = 0.0;        // opening angle in the current state, radians
};

struct FabricationData {
  std::vector<FabricationRod> rods;      // in rod order
  std::vector<FabricationJoint> joints;  // in joint (vertex) order
};

// The fabrication data of `linkage`: its rest state (cut lengths, stations)
// and its current state (opening angles).
FabricationData fabrication_data(const RodLinkage& linkage);

const char* family_name(RodFamily family);  // "A" or "B"

}  // namespace xshell
