#pragma once
// Generator of a 3D deck at the scale of a commercial finite-element model:
// simply supported spans of concrete (8-node hexahedra, lumped mass), of a
// solid rectangular section or a single-cell box girder,
// carrying rails on pads (direct fastening: no sleepers, no ballast). The
// rails continue over approach and exit lengths on rigid ground, so a long
// train can start on the track. The mesh is refined to a requested number
// of DOFs. Built for the seed-scale benchmark and `vsi generate deck-3d`
// (which writes it as Matrix Market files for the import path).
//
// Axes: x along the track (0 at the first support), y across (0 on the deck
// centreline), z up (0 at the soffit).
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "model/structure_model.hpp"

namespace railvsi {

// Elements along x of each span, across the width, through the depth. For a
// box girder, the ny x nz grid has lines on every slab and web face (ny
// even, a line on the centreline) and only its cells inside the plates are
// elements.
struct Deck3dMesh {
  std::vector<int> nx;
  int ny = 2;
  int nz = 1;
};

// A single-cell box girder, symmetric about the deck centreline: vertical
// webs whose outer faces are the edges of the bottom slab, a top slab
// across the full width (overhanging the webs by the difference), and a
// solid diaphragm in the end element of each span (one element, L / nx
// thick; without it the end sections would rack freely). The
// defaults are an illustrative section, not a design: A = 4.51 m^2,
// I = 2.60 m^4, Bredt's J = 5.95 m^4, polar moment 19.9 m^4.
struct BoxGirderSection {
  double top_width_m = 7.0;
  double top_thickness_m = 0.3;
  double bottom_width_m = 5.0;  // outer face to outer face of the webs
  double bottom_thickness_m = 0.25;
  double web_thickness_m = 0.4;
  double depth_m = 2.0;  // soffit to top of the top slab
  // Solid diaphragms inside each span besides the end ones, evenly spaced
  // (at L m / (n + 1)), each one element long: they hold the cell's shape
  // against racking, which lowers the torsion frequency of a box without
  // them.
  int intermediate_diaphragms = 0;
};

struct Deck3dOptions {
  std::vector<double> spans_m{25.0, 25.0, 25.0};
  // Solid rectangular section: with the defaults EI = 8.1e10 N*m^2,
  // 28 t/m, first bending frequency 4.3 Hz at 25 m. Not used when `box`
  // is given.
  double width_m = 7.0;
  double depth_m = 1.6;
  std::optional<BoxGirderSection> box;
  double E_Pa = 34.0e9;                  // C35/45, EN 1992-1-1 Table 3.1 (Ecm)
  double poisson = 0.2;                  // EN 1992-1-1 3.1.3(4), uncracked
  double density_kg_per_m3 = 2500.0;     // reinforced concrete, EN 1991-1-1 Table A.1
  double damping_ratio = 0.01;           // EN 1991-2 Table 6.6, prestressed concrete, L >= 20 m
  // Total DOFs (deck and rails, after supports) the mesh is refined to,
  // within 5 %; ignored when `mesh` is given.
  int target_dofs = 230000;
  std::optional<Deck3dMesh> mesh;
  // Rails, per rail: Zhai, Wang & Lin (2004), J. Sound Vib. 270, 673-683, whose values
  // lump both rails, halved.
  double rail_EI_Nm2 = 2.059e11 * 3.217e-5;
  double rail_mass_kg_per_m = 60.64;
  double pad_k_N_per_m = 3.25e7;         // per rail seat
  double pad_c_Ns_per_m = 3.75e4;
  double sleeper_spacing_m = 0.6;        // rail node and pad spacing
  std::vector<double> rail_y_m{-0.75, 0.75};  // one rail line per entry (standard gauge rail centres)
  // Track on rigid ground before and after the bridge. 400 m holds the
  // longest library trains (KHST, Eurostar: 380 m) before the bridge.
  double approach_m = 400.0;
  double exit_m = 40.0;
};

struct Deck3d {
  std::shared_ptr<const StructureModel> model;
  Deck3dMesh mesh;
  // Deck nodes, span by span, on the full ny x nz grid: position (x, y, z)
  // and DOFs (u, v, w; -1 fixed, or all -1 for a node in a box's void).
  std::vector<std::array<double, 3>> node_m;
  std::vector<std::array<int, 3>> node_dofs;
  // The section as modelled (deck_section_properties).
  double section_area_m2 = 0.0;
  double section_I_m4 = 0.0;      // about the horizontal centroidal axis
  double section_J_m4 = 0.0;      // St Venant torsion constant
  double section_polar_m4 = 0.0;  // polar moment about the centroid
};

// Of the section as modelled (gross concrete, the rails not included).
struct DeckSectionProperties {
  double area_m2 = 0.0;
  double I_m4 = 0.0;         // about the horizontal centroidal axis (vertical bending)
  double I_lateral_m4 = 0.0; // about the vertical axis (lateral bending)
  double polar_m4 = 0.0;     // I_m4 + I_lateral_m4: rho * polar_m4 is the torsional inertia per metre
  double centroid_z_m = 0.0; // above the soffit
  // St Venant torsion constant: for the box, Bredt's J = 4 A_m^2 / (sum of
  // s/t over the plates' mid-lines), A_m the area they enclose (Bredt
  // 1896; Timoshenko & Goodier, Theory of Elasticity, 3rd ed., 1970,
  // section 115); for the rectangle, the series of Timoshenko & Goodier
  // section 109.
  double torsion_J_m4 = 0.0;
};

DeckSectionProperties deck_section_properties(const Deck3dOptions& options);
// Checks the box alone; InputError paths relative to it ("/web_thickness_m").
void check_box_girder(const BoxGirderSection& box);

// Throws InputError (paths relative to the options, e.g. "/target_dofs") on
// bad options or a target out of reach.
Deck3dMesh choose_deck_3d_mesh(const Deck3dOptions& options);
// DOFs of the model built with this mesh, without building it.
long deck_3d_dofs(const Deck3dOptions& options, const Deck3dMesh& mesh);
Deck3d make_deck_3d(const Deck3dOptions& options);

}  // namespace railvsi
