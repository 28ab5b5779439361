// The crack cutter's tolerances (cut/crack_cutter.h): where crossings snap to corners, when
// the blade's crossings are temporary points, when the blade lies in the plane of faces, and how
// far a step looks. Lengths are shares of the tissue's edge length there unless said otherwise.
#pragma once

#include <cstddef>

namespace kerf::cut {

// Progressive: a piece on the blade lower than this fraction of the smallest height of the tet
// it stands in for is softened (CrackCutter::StiffnessScale): the elastic model makes it no
// stiffer than a piece of this height, so the slivers a blade near an edge makes do not slow the
// implicit solve, while the opening still follows the blade.
inline constexpr double kDefaultMinTemporaryHeight = 0.02;

// Crossings closer than this to a corner are always taken at it, whatever the snap fraction.
inline constexpr double kMinSnapFraction = 0.01;
inline constexpr double kDefaultCrackSnapFraction = 0.2;
// An edge's crossing farther from its nearer corner than the snap share, but within this many
// times it, snaps too where a piece under kSliverAngleDeg would come of it: where bisecting a tet
// at the edge at that point leaves a half under that angle (rest positions). With the default
// fraction, crossings 0.2-0.35 of an edge from a corner, of which most of the slivers cut into
// meshes of uneven tets came (docs/cutting-fidelity.md). None with the least snapping (a snap
// fraction of kMinSnapFraction or less).
// It snaps too (or moves off) where its edge meets another edge of a tet around it at that
// corner under kThinCornerDeg: a point there makes a thin triangle whatever the split (two thirds
// of the slivers left on liver.msh's hand paths came of such corners: docs/cutting-fidelity.md).
inline constexpr double kSliverSnapScale = 1.75;
inline constexpr double kSliverAngleDeg = 5;
inline constexpr double kThinCornerDeg = 15;
// A vertex snaps onto the crack only within this share of the smallest mean edge of the tets
// around it from the step's swept surface (just under the fidelity meter's tolerance, 0.25 of the
// tet's: lab/crack_fidelity.h), so no crack face bends farther than that from the blade's path
// to reach it.
inline constexpr double kSnapReach = 0.24;
// Where the blade is withdrawn, a face's crossing beside an edge the crack crossed elsewhere stays
// a point of the face if moving it off the face's edges takes it no farther than this share of the
// tissue's edge there (half the snap reach, leaving the other half to the crack faces between it
// and the apex: at 0.24, 60 more crack faces of 960 hand cuts lay beyond the fidelity meter's
// tolerance; docs/cutting-fidelity.md).
inline constexpr double kWithdrawnPointShift = 0.12;
// A split of a tet for good leaving samples of the blade's steps inside the tet farther than
// this share of the tissue's edge there from its crack gives way to a cone through the farthest
// (CrackCutter::ApexCoveringTheSteps): under the fidelity meter's tolerance (0.25 of the tet's
// mean edge, lab/crack_fidelity.h), for the samples lie only in the tet and the meter's anywhere.
inline constexpr double kStepCoverReach = 0.2;
// Such a cone's smallest dihedral angle, degrees, at the least: thinner cones through samples
// (5-10 degrees) let the liver's progressive live cut without snapping, under backward Euler and
// the corotational law, reach 10 times its first pose's energy (tests/lab/live_cut_test.cc).
inline constexpr double kCoveringConeAngleDeg = 10;
// The samples tried as such a cone's apex besides the farthest, spread evenly (the farthest's
// cone is often under the angle where the blade turned inside the tet; 32 measured the same).
inline constexpr int kCoveringApexCandidates = 16;
// The crack runs along an edge between two vertices snapped onto it where the edge's middle lies
// within this share of the tissue's edge there of the surface the blade swept between the two
// snaps (beyond the fidelity meter's tolerance for a crack face's middle, 0.25, so a curved
// sweep keeps its edges), looked for over at most kJoinSteps steps back (farther back, it does).
inline constexpr double kJoinReach = 0.3;
inline constexpr std::size_t kJoinSteps = 8192;
// The blade sweeps along the tissue's surface at a vertex where the normal of the surface it swept
// and the surface's there are within about 26 degrees (the cosine of the angle between them
// is over this): a vertex there snapped onto the crack would lay the crack on the surface.
inline constexpr double kAlongSurfaceCosine = 0.9;
// The blade's crossing of a face is a temporary point unless it is within this (barycentric) of
// the face's edges; temporary points are not snapped, so the crack follows the blade closely
// (their thin pieces last only while the blade is in their tet).
inline constexpr double kMinTemporaryWeight = 1e-3;
// The blade passes through an edge (lying in its plane, or its tip on it) when it comes this
// near it, in the edge's length: the blade sweeping in the plane of faces crosses none of their
// edges, and its crossings of them are temporary points so the crack follows it there too. As
// large as the distance from the edge of a face's crossing too near it to be a point of its own
// (kMinTemporaryWeight, on a face up to twice as high as the edge is long): a blade nearly in the
// plane of faces crosses every face that near an edge, and left the tets it was in whole.
inline constexpr double kInPlaneTolerance = 2 * kMinTemporaryWeight;
// A step looks at the tets in the box of the surface the blade swept and, where the blade is long
// and oblique to the axes, only at those within this many grid cells (about a mean edge each) of
// it: those it crossed, those with a vertex it may snap (within a fraction of an edge of it) and
// those whose vertices moved onto it since the last pose.
inline constexpr double kStepMargin = 0.5;

}  // namespace kerf::cut
