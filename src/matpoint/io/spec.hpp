// Spec: the validated, plain-struct form of an input file (DESIGN.md data flow: input.json -> Spec).
// Every field here has passed validation; the simulation never re-checks user input.
#pragma once

#include <array>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "matpoint/mesh/triangle_pattern.hpp"

namespace matpoint {

using Triple = std::array<double, 3>;  // unused trailing components are zero

enum class UpdateScheme { USL, USF, MUSL, USAVG, USAVGPlus };  // Nairn 2026 §2.1 (MUSL = "USL+")
enum class VelocityTransfer { FLIP, PIC, Blend, FMPM, XPIC };  // particle velocity update
// Grid basis (docs/input.md#solver): point bases, GIMP family, CPDI family.
enum class ShapeKind { Linear, BSpline2, BSpline3, UGIMP, CpGIMP, CPDI1, CPDI2, B2GIMP, B2CPDI };
enum class DeformationUpdate { Exponential, Linear };  // dF = exp(L dt) or I + L dt
enum class MaterialModel {
  LinearElastic,
  NeoHookean,
  MieGruneisen,
  Rigid,
  MohrCoulomb,
  DruckerPrager,
  VonMises
};
enum class NeoHookeanVolumetric { LogJ, HalfJSquared };  // lambda lnJ/J  or  lambda/2 (J - 1/J)
enum class DruckerPragerMatch {
  Outer,
  Inner,
  PlaneStrain
};  // cone through MC's compression/extension edges, or plane strain

struct GridSpec {
  int dim = 2;
  Triple min{}, max{};
  Triple cell_size{};          // per direction
  std::array<int, 3> cells{};  // (max - min) / cell_size, exact
};

/// A scalar function of time: a constant (one value) or a piecewise-linear table, held constant
/// outside its range.
struct TimeFunction {
  std::vector<double> times;   // empty for a constant
  std::vector<double> values;  // one value for a constant
  [[nodiscard]] double operator()(double t) const;
  /// The integral from 0 to t (t >= 0), exact for the piecewise-linear table.
  [[nodiscard]] double integral(double t) const;
};

struct MaterialSpec {
  std::string name;
  MaterialModel model = MaterialModel::LinearElastic;
  double density = 0;
  double youngs_modulus = 0, poisson_ratio = 0;  // always filled (converted when lambda/mu are given)
  double lambda = 0, mu = 0;                     // always filled
  NeoHookeanVolumetric volumetric = NeoHookeanVolumetric::LogJ;
  // mie_gruneisen (material/mie_gruneisen.hpp): U_s = C0 + S u_p, Gamma0; mu is its shear modulus
  double bulk_sound_speed = 0, hugoniot_slope = 0, gruneisen = 0;
  // mohr_coulomb, drucker_prager (material/mohr_coulomb.hpp, drucker_prager.hpp): c, phi, psi in
  // degrees, optional linear softening to (c_r, phi_r) at plastic strain eps_s (0: none)
  double cohesion = 0, friction_angle = 0, dilation_angle = 0;
  double residual_cohesion = 0, residual_friction_angle = 0, softening_strain = 0;
  double tension_cutoff = std::numeric_limits<double>::infinity();  // mohr_coulomb: sigma_t (none: infinite)
  DruckerPragerMatch match = DruckerPragerMatch::PlaneStrain;
  // von_mises (material/von_mises.hpp): initial yield stress and linear hardening modulus
  double yield_stress = 0, hardening_modulus = 0;
  // von_mises, optional Johnson-Cook terms (B eps_p^n hardening, C ln(rate / reference rate));
  // B = C = 0: none
  double jc_b = 0, jc_n = 1, jc_c = 0, jc_reference_rate = 1;
  // Rigid: the prescribed velocity of its particles, one function of time per component (zero by
  // default); a rigid material feels no stress and needs "contact" (docs/theory/contact.md).
  std::array<TimeFunction, 3> rigid_velocity{TimeFunction{{}, {0.0}}, TimeFunction{{}, {0.0}},
                                             TimeFunction{{}, {0.0}}};
  // Coupled heat conduction (HeatSpec): heat capacity C_V (J/(kg K)), conductivity kappa
  // (W/(m K)) and the linear thermal expansion coefficient alpha (1/K; linear_elastic and
  // neo_hookean only). Read only when the input has a "heat" section.
  double heat_capacity = 0, conductivity = 0, thermal_expansion = 0;
};

// GradedDisk: Aulisa & Capodaglio's disk of a uniform core and boundary layers refined towards the
// surface (their Appendix A, as their code builds it: particles/graded_generators.hpp).
enum class BodyShape { Box, Disk, Polygon, GradedDisk, GradedBeam };

struct BodySpec {
  std::string name;
  int material = 0;  // index into Spec::materials
  BodyShape shape = BodyShape::Box;
  Triple min{}, max{};  // Box (interval / rectangle / box)
  Triple center{};      // Disk (disk in 2-D, sphere in 3-D, interval in 1-D)
  double radius = 0;
  std::vector<std::array<double, 2>> polygon;  // Polygon (2-D only), counter-clockwise or clockwise
  int particles_per_cell = 2;                  // per direction
  Triple velocity{};                           // initial velocity (uniform part)
  // Optional sine field added to it: amplitude * sin(wave_vector . x + phase), e.g. a bar's first mode.
  bool has_sine_velocity = false;
  Triple sine_amplitude{}, sine_wave_vector{};
  double sine_phase = 0;
  // Optional linear part: V += velocity_gradient x (rows: components), e.g. a uniform stretching.
  bool has_velocity_gradient = false;
  std::array<Triple, 3> velocity_gradient{};
  // Optional seeded Gaussian noise added to every velocity component: amplitude * N(0, 1), the
  // seed of a stability scan (Gong 2015 extraction S1).
  double noise_amplitude = 0;
  unsigned noise_seed = 1;
  // Optional geostatic initial stress (plastic materials; material/material.hpp set_geostatic_stress):
  // sigma_v = -rho g (surface - height), horizontal stresses k0 sigma_v.
  bool geostatic = false;
  double k0 = 0, geostatic_surface = 0;
  // GradedDisk and GradedBeam (last: aggregate initialisers elsewhere list the members above in order)
  double core_radius = 0;      // R0, the disk's uniform core
  int core_divisions = 300;    // N_theta0, particles on the disk core's outer ring; the beam's N_H rows
  double layer_growth = 1.14;  // f: each layer 1/f as thick, f times as many particles
  double core_height = 0;      // H0, the beam's uniform core (box min/max: the beam)
  bool gauss_points =
      false;  // particles at the 2- or 3-point Gauss-Legendre points per direction (particles_per_cell 2, 3)
  // placement "gauss" on a structured T3 mesh: 3 particles per triangle, the cells split as the mesh's
  std::optional<mesh::TrianglePattern> triangle_points;
};

enum class ConditionKind { Fixed, Slip, Velocity, MovingWall };

struct VelocityConditionSpec {
  bool on_face = true;  // face of the domain, or a box of nodes
  int face_axis = 0;    // 0, 1, 2 for x, y, z
  int face_side = 0;    // 0: min face, 1: max face
  Triple box_min{}, box_max{};
  ConditionKind kind = ConditionKind::Fixed;
  int normal_axis = 0;  // Slip: the constrained (normal) axis; a face's own axis by default
  // Fixed / Slip on a face: act only on nodes moving into the face (v . outward normal > 0) and
  // leave the others free, so a body can roll off or lift off (examples/rolling-disk).
  bool one_sided = false;
  std::array<std::optional<TimeFunction>, 3> velocity;  // Velocity: prescribed components, empty = free
  // MovingWall (Nairn 2026 §3.1): a plane x_axis = position + integral of wall_velocity that sets
  // the axis velocity of the nodes with mass on its far side and of those within `depth` inside
  // the material; uniform wall velocity, or a linear profile through the fixed point stretch_about.
  double wall_position = 0;
  bool material_below = true;  // the material lies at smaller coordinates than the wall
  TimeFunction wall_velocity;
  double depth = 0;
  std::optional<double> stretch_about;
  // Implicit runs: the condition holds on the nodes of a named mesh boundary (a structured mesh's
  // "left", "right", "bottom", "top", "back", "front", or a Gmsh physical group), and `receding`
  // is the receding-contact constant C_c of its faces (Aulisa & Capodaglio §5; 0: none).
  std::string boundary;
  double receding = 0;
};

/// The element mesh of an implicit run (mesh/): a structured rectangle or box, graded per axis and
/// refined `refine` times (Aulisa & Capodaglio's level J), or a Gmsh .msh file. T3: the Q4 cells
/// split into triangles as `diagonal` says. BSpline2: a patch of C1 quadratic B-splines on equal
/// cells (mesh/element_types.hpp).
enum class MeshElement { Q4, Q9, Hex8, T3, FromFile, BSpline2 };
struct MeshSpec {
  bool enabled = false;
  MeshElement element = MeshElement::Q9;
  Triple min{}, max{};
  std::array<int, 3> cells{};  // coarse elements per direction
  Triple ratio{1, 1, 1};       // geometric growth of the element size along each axis
  std::array<std::vector<double>, 3>
      lines;         // mesh.lines: the coarse lines per axis (then min, max, cells follow)
  int refine = 0;    // uniform midpoint refinements
  std::string file;  // a Gmsh .msh file instead of the structured mesh
  mesh::TrianglePattern diagonal = mesh::TrianglePattern::Alternating;  // T3: how the cells are split
};

/// loads.tractions[k] of an implicit run: a surface load on the faces of a named mesh boundary,
/// either a pressure p(t) (normal to the boundary's current position, positive pushing into the
/// body: a follower load) or a traction vector t(t) per unit length (area) of the boundary as meshed
/// (fixed direction). Both act on the mesh's faces: where the body fills the mesh up to that boundary.
struct SurfaceLoadSpec {
  std::string boundary;
  std::optional<TimeFunction> pressure;
  std::array<std::optional<TimeFunction>, 3> traction;  // components (absent: 0) when no pressure
};

/// fe_bodies[k] of an implicit run (Aulisa & Capodaglio §4; fem/fe_body.hpp): mesh elements that
/// form a total-Lagrangian finite element body instead of background grid: those of a mesh element
/// set (a Gmsh physical group of dimension dim) or those whose centre lies in [region_min, region_max].
struct FeBodySpec {
  std::string name;
  std::string elements;  // a mesh element set; empty: region
  Triple region_min{}, region_max{};
  int material = 0;
  bool gravity = true;                // the body takes loads.gravity (the paper's coupled tests: false)
  bool unit_inertia_density = false;  // "inertia": "unit_density": the authors' code's FEM inertia (A2)
  double interface_receding = 0.0;    // C_c of the background faces on the body (§5, eq. (47))
};

struct LoadSpec {
  Triple gravity{};
  std::vector<SurfaceLoadSpec> tractions;  // implicit runs only
  // loads.gravity_scale: the gravity is gravity_scale(t) * gravity (e.g. switched off after a
  // while: Aulisa & Capodaglio's Test B). The explicit step takes it at the step's start, the
  // implicit one at its end (the time of the equilibrium it solves).
  TimeFunction gravity_scale{{}, {1.0}};
};

/// FMPM(k) and XPIC(k) settings (Nairn 2026 §2.2-3.4; docs/theory/fmpm.md).
enum class FmpmMeasure { None, Means, Changes };          // dynamic FMPM convergence measure (§3.4)
enum class FmpmBoundaryMethod { Incremental, Combined };  // §3.1: new method, or the old "combined"
enum class FmpmRecursion { Incremental, Binomial };       // eq. (6), or eq. (4) (for verification)
enum class FmpmPeriod { EveryStep, Courant, Steps, Time };

struct FmpmSpec {
  int order = 2;              // k: the number of terms of the series m~_k^-1 (k = 1: lumped)
  int blend_with = 0;         // 0: no blending; m >= 1: blend with FMPM(m) (§3.3)
  double blend_factor = 1.0;  // alpha_b
  FmpmMeasure measure = FmpmMeasure::None;
  double limit = 0.0;  // dynamic FMPM: stop when the measure falls below this
  FmpmBoundaryMethod boundary_method = FmpmBoundaryMethod::Incremental;
  FmpmRecursion recursion = FmpmRecursion::Incremental;
  FmpmPeriod period = FmpmPeriod::EveryStep;  // periodic FMPM: FLIP in the other steps
  double period_value = 0.0;                  // Courant units C_X, a step count, or a time
};

/// Particle-to-grid mapping (docs/input.md#solver, docs/theory/impm.md): mass-weighted MPM; Gong
/// 2015's IMPM (§5.4: MLS velocity to the nodes, MLS density/stress/body force to cell points,
/// cell quadrature); or only the MLS velocity (with a CPDI shape: improved CPDI, §6.6).
enum class Mapping { MPM, IMPM, MlsVelocity };
enum class CellQuadrature { Centre, Gauss2 };      // one point (eqs. 5.9-5.14), or 2^D Gauss points (A18)
enum class CellVolume { Full, ParticleFraction };  // Omega_c = cell volume (as printed), or sum of V_p (A17)

struct MlsSpec {
  int degree = 1;  // 1: linear basis (Gong's "second-order MLS"), 0: Shepard (extraction A14)
  CellQuadrature quadrature = CellQuadrature::Centre;
  CellVolume cell_volume = CellVolume::Full;
};

/// The implicit MPMs and their options: Aulisa & Capodaglio's particle-Newmark MPM (§3; Newmark at
/// the particles) and Iaconeta 2017's updated-Lagrangian MPM (§4.1, Algorithm 1; Newmark at the
/// grid nodes from the particles' projected velocity and acceleration).
enum class SolverKind { Explicit, ImplicitMpm, ImplicitUl };
// petsc: PETSc KSP on MPI ranks (a build with -DMATPOINT_PETSC=ON; implicit/petsc_solver.hpp)
enum class LinearSolverChoice { Umfpack, Klu, BiCgStab, Gmres, Petsc };
enum class SoftStiffnessRule { Paper, Code };  // M_E by the paper's rule, or the authors' code's (A13)
// solver.basis of an implicit run: the mesh's element functions (MPM), or Iaconeta 2017's Galerkin
// meshfree method (§4.2) with MLS or LME functions on the mesh's nodes (shape/meshfree_stencils.hpp)
enum class ImplicitBasis { Mesh, Mls, Lme };
struct MeshfreeSpec {                         // solver.meshfree, multiples of the nodal spacing h
  double radius_factor = 2.8284271247461903;  // R / h = 2 sqrt(2) (extraction A5)
  std::optional<double> dilation_factor;      // MLS R_eff / h; empty: R / 2
  double gamma = 1.8;                         // LME beta h^2 (eq. (61))
  int min_nodes = 0;                          // MLS repair: variable radius (0: off; §6.5: 6)
  int lme_max_nodes = 0;                      // LME repair: augment the cloud up to this (0: off)
  std::optional<double> spacing;              // h; empty: the mesh's smallest cell size
  bool mls_truncated_weight = false;  // mls_weight "truncated" (the authors' code) or "smooth" (C1 at R)
  bool delete_failed_points = false;  // drop points without usable functions (the authors' code, §6.5)
  bool carried_node_history = false;  // node_history "carried" (Algorithm 2) or "projected" (ours)
};
struct ImplicitSpec {
  double beta = 0.3, gamma = 0.5;  // Newmark, eqs. (17)-(19); the paper's tests use 0.3 / 0.5
  bool initial_acceleration_from_body_force = false;  // a^0 = 0 (the paper) or a^0 = b (A17)
  bool static_analysis = false;       // no inertia: each step solves equilibrium under the load at its end
  bool small_strain = false;          // geometrically linear, Hooke's law (the linear FEM / Timoshenko check)
  double increment_tolerance = 1e-9;  // Newton: ||du_c|| / ||u_c|| per component (A16)
  int max_iterations = 20;
  double residual_tolerance = 0;  // optional ||R|| / ||R_0|| test; 0: off
  bool line_search = false;
  int max_step_cuts = 4;  // a diverging step is halved and retried this many times
  LinearSolverChoice linear_solver = LinearSolverChoice::Umfpack;
  SoftStiffnessRule flag_rule = SoftStiffnessRule::Paper;
  std::vector<std::pair<int, double>> soft_stiffness;  // (M_E upper bound, C_E): C_E for M_E < bound
  bool receding_in_gradient = true;                    // A24: grad_x N from the corrected nodes
  ImplicitBasis basis = ImplicitBasis::Mesh;
  MeshfreeSpec meshfree;  // basis mls or lme
  // Time-step control: solver.dt (fixed), or a user schedule dt(t) taken at each step's start, or
  // adaptive on Newton's iteration count (implicit/step_size_control.hpp).
  std::optional<TimeFunction> dt_schedule;
  // Or dt as a function of the lowest particle's coordinate along dt_position_axis, read at each
  // step's start (solver.implicit.dt_by_position: the step near a plate, Aulisa & Capodaglio Test D, A18).
  std::optional<TimeFunction> dt_by_position;
  int dt_position_axis = 1;
  struct Adaptive {
    bool enabled = false;
    double min = 0, max = 0;  // dt bounds
    int easy_iterations = 3;  // a step that converged in at most this many iterations: dt * factor
    int hard_iterations = 8;  // at least this many: dt / factor
    double factor = 1.5;
  } adaptive;
};

/// solver.rebalance: when a run on several MPI ranks cuts its boxes anew by particle count
/// (docs/scale-out.md §10). The results do not depend on it: only the time they take.
struct RebalanceSpec {
  bool enabled = true;
  double imbalance = 1.15;  // re-partition when the most particles on a rank exceed the mean by this factor
  long min_steps = 100;     // and at least this many steps after the start or the last re-partition
};

struct SolverSpec {
  SolverKind kind = SolverKind::Explicit;
  [[nodiscard]] bool is_implicit() const { return kind != SolverKind::Explicit; }
  ImplicitSpec implicit;
  UpdateScheme scheme =
      UpdateScheme::MUSL;  // see docs/input.md: robust with FLIP, energy within 0.1 % in two-disks
  VelocityTransfer transfer = VelocityTransfer::FLIP;
  double position_alpha = 1.0;  // Nairn 2026 eq. (7) alpha_t; default 1 for FLIP/PIC/blend, 1/2 for FMPM
  double flip_fraction = 1.0;   // Blend: V = f V_FLIP + (1 - f) V_PIC
  FmpmSpec fmpm;                // transfer fmpm or xpic
  ShapeKind shape = ShapeKind::Linear;
  Mapping mapping = Mapping::MPM;
  MlsSpec mls;  // mapping impm or mls_velocity
  DeformationUpdate deformation_update = DeformationUpdate::Exponential;
  std::optional<double> dt;  // fixed time step, or
  double courant = 0.5;      // Courant number with the largest material wave speed
  double end_time = 0;
  long max_steps = 0;  // 0: no limit
  // Nodes at or below this fraction of the largest particle mass are inactive. 0 (the default):
  // every node a particle reaches is active, which conserves momentum exactly (docs/input.md).
  double mass_tolerance = 0.0;
  // Gong 2015 extraction A24: the velocity conditions also hold on the old node velocities, so the
  // FLIP increment carries no boundary reaction (input key solver.constrain_old_velocity, default false).
  bool constrain_old_velocity = false;
  // The energy-growth guard (run/energy_guard.hpp): stop when the energy balance rises by
  // more than this many times the energy scale; empty: off ("off" in the input).
  std::optional<double> max_energy_growth = 1.0;
  // Artificial bulk viscosity coefficients A1 (linear), A2 (quadratic); zero: off.
  double av_linear = 0.0, av_quadratic = 0.0;
  RebalanceSpec rebalance;  // decomposed explicit runs (mpirun -n P)
};

/// output.checkpoint: when a run writes DIR/checkpoint.h5 (docs/output.md "Checkpoints and restart").
struct CheckpointSpec {
  long every_steps = 0;      // 0: not by step count
  double every_minutes = 0;  // 0: not by wall-clock time
  [[nodiscard]] bool enabled() const { return every_steps > 0 || every_minutes > 0; }
};

/// A probe: the particle whose reference position is nearest `position` (ties: the lowest id),
/// recorded at every output in history.csv (analysis/probes.hpp).
struct ProbeSpec {
  std::string name;  // letters, digits, '_' and '-': it names history.csv columns
  Triple position{};
};

struct OutputSpec {
  long every_steps = 0;   // 0: use every_time
  double every_time = 0;  // 0 and every_steps == 0: first and last state only
  bool particles = true;  // write particles_NNNNNN.vtu + results.pvd
  // Implicit runs: mesh nodes whose last-step displacement history.csv records (the node nearest
  // each position; the whole displacement in a single-step static analysis).
  std::vector<ProbeSpec> node_probes;
  bool plots = true;                // write plots/*.png at the end (needs python3-matplotlib)
  std::vector<std::string> fields;  // particle fields written to .vtu; empty = all
  CheckpointSpec checkpoint;
  std::vector<ProbeSpec> probes;
  // Steps are shortened to land exactly on the every_time output times (not an input key: the
  // stability scan turns it off, so that every step runs at the scanned Courant number).
  bool exact_times = true;
};

/// What a check's reference is (docs/verification.md counts them apart): independent of the code
/// (analytic, a paper, a converged finer run), a value of an earlier run of the code, or a guard
/// that catches only gross failure.
enum class CheckKind { Verification, Regression, Guard };

/// A reference value the run compares itself against (summary.json "checks").
struct CheckSpec {
  std::string name;
  std::string measure;  // a name from analysis/measures.hpp
  double expected = 0;
  double tolerance = 0;  // pass when |measured - expected| <= tolerance
  std::string source;
  CheckKind kind = CheckKind::Verification;
};

/// Multimaterial contact (Nairn 2026 §3.2; docs/theory/contact.md): each body (or material) gets
/// its own grid velocity field, and nodes shared by two or more fields get a contact law.
enum class ContactLaw { Stick, Frictionless, Coulomb };
// one field's mass gradient, both fields' volume gradients, or Nairn's logistic regression
enum class ContactNormals { MassGradient, Average, Logistic };
enum class ContactFmpmMethod { Net, Evolving };  // increments inside the FMPM loop (§3.2)

struct ContactLawSpec {
  ContactLaw law = ContactLaw::Stick;
  double friction = 0.0;  // Coulomb coefficient mu
};

struct ContactPairSpec {
  int first = 0, second = 0;  // field indices (bodies, or materials when by_material)
  ContactLawSpec law;
};

struct ContactSpec {
  bool enabled = false;
  bool by_material = false;  // one field per material instead of one per body
  ContactLawSpec law;        // every pair not listed in pairs
  std::vector<ContactPairSpec> pairs;
  ContactNormals normals = ContactNormals::Logistic;
  std::optional<double> separation;  // position criterion: contact needs (x_b - x_a) . n < separation * h
  ContactFmpmMethod fmpm_method = ContactFmpmMethod::Net;
};

/// Coupled heat conduction in the explicit solver (Nairn 2026 §3.2.2, §3.5; docs/theory/heat.md):
/// a temperature per particle, conducted on the grid with the nodal capacity sum_p M_p C_V S_pi,
/// heated by friction and thermoelastic coupling. Off unless the input has a "heat" section.
enum class HeatTransfer { FLIP, FMPM };  // T_p += S dT_i, or T_p = S T+(k) (transport FMPM(k))
enum class ThermalConditionKind { Temperature, Flux };
// Heat across a contact surface (contact runs; docs/theory/heat.md "Contact"): one temperature per
// contact node, an interface conductance h_c, or none.
enum class ThermalContact { Perfect, Conductance, Insulated };

struct ThermalConditionSpec {
  int face_axis = 0, face_side = 0;  // as VelocityConditionSpec's faces
  ThermalConditionKind kind = ThermalConditionKind::Temperature;
  double value = 0;  // the temperature, or the heat flux into the domain per unit face area
};

struct HeatSpec {
  bool enabled = false;
  double initial_temperature = 300;  // T0: every particle's initial and the reference temperature
  bool conduction = true;            // false: adiabatic (no conduction; the sources stay local)
  bool thermoelastic = true;         // heating -3 K alpha T tr(D) / (rho0 C_V) where alpha > 0
  bool friction = true;              // contact's frictional work becomes heat at its nodes
  HeatTransfer transfer = HeatTransfer::FLIP;
  int fmpm_order = 2;  // transfer fmpm: k of the capacity series
  // Optional sine added to T0: amplitude * sin(wave_vector . x + phase) (a conduction mode)
  bool has_sine = false;
  double sine_amplitude = 0;
  Triple sine_wave_vector{};
  double sine_phase = 0;
  std::vector<ThermalConditionSpec> conditions;  // faces not listed: zero flux
  ThermalContact contact = ThermalContact::Perfect;
  double contact_conductance = 0;                         // h_c, W/(m^2 K) (ThermalContact::Conductance)
  std::vector<std::pair<int, double>> body_temperatures;  // (body, initial temperature) in place of T0
};

struct Spec {
  std::string title;
  GridSpec grid;  // implicit runs: the mesh's bounding box and mean element size (particle seeding)
  MeshSpec mesh;
  std::vector<MaterialSpec> materials;
  std::vector<BodySpec> bodies;
  std::vector<FeBodySpec> fe_bodies;  // implicit runs only
  std::vector<VelocityConditionSpec> conditions;
  LoadSpec loads;
  SolverSpec solver;
  OutputSpec output;
  std::vector<CheckSpec> checks;
  ContactSpec contact;
  HeatSpec heat;
  nlohmann::json echo;  // the input as read (comments stripped), echoed into summary.json
};

}  // namespace matpoint
