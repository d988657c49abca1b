// The keywords of the input format and the values they stand for (docs/input.md lists them).
#pragma once

#include <array>

#include "matpoint/io/input/json_value.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint::input_detail {

constexpr std::array<Named<MaterialModel>, 7> kModels{{{"linear_elastic", MaterialModel::LinearElastic},
                                                       {"neo_hookean", MaterialModel::NeoHookean},
                                                       {"mie_gruneisen", MaterialModel::MieGruneisen},
                                                       {"rigid", MaterialModel::Rigid},
                                                       {"mohr_coulomb", MaterialModel::MohrCoulomb},
                                                       {"drucker_prager", MaterialModel::DruckerPrager},
                                                       {"von_mises", MaterialModel::VonMises}}};
constexpr std::array<Named<DruckerPragerMatch>, 3> kDruckerPragerMatches{
    {{"outer", DruckerPragerMatch::Outer},
     {"inner", DruckerPragerMatch::Inner},
     {"plane_strain", DruckerPragerMatch::PlaneStrain}}};
constexpr std::array<Named<ContactLaw>, 3> kContactLaws{{{"stick", ContactLaw::Stick},
                                                         {"frictionless", ContactLaw::Frictionless},
                                                         {"coulomb", ContactLaw::Coulomb}}};
constexpr std::array<Named<ContactNormals>, 3> kContactNormals{
    {{"mass_gradient", ContactNormals::MassGradient},
     {"average", ContactNormals::Average},
     {"logistic_regression", ContactNormals::Logistic}}};
constexpr std::array<Named<ContactFmpmMethod>, 2> kContactFmpmMethods{
    {{"net", ContactFmpmMethod::Net}, {"evolving", ContactFmpmMethod::Evolving}}};
constexpr std::array<Named<CheckKind>, 3> kCheckKinds{{{"verification", CheckKind::Verification},
                                                       {"regression", CheckKind::Regression},
                                                       {"guard", CheckKind::Guard}}};
constexpr std::array<Named<bool>, 2> kContactFields{{{"bodies", false}, {"materials", true}}};
constexpr std::array<Named<NeoHookeanVolumetric>, 2> kVolumetric{
    {{"log_j", NeoHookeanVolumetric::LogJ}, {"half_j_squared", NeoHookeanVolumetric::HalfJSquared}}};
constexpr std::array<Named<BodyShape>, 6> kShapes{{{"box", BodyShape::Box},
                                                   {"disk", BodyShape::Disk},
                                                   {"sphere", BodyShape::Disk},  // 3-D only
                                                   {"polygon", BodyShape::Polygon},
                                                   {"graded_disk", BodyShape::GradedDisk},
                                                   {"graded_beam", BodyShape::GradedBeam}}};
constexpr std::array<Named<ConditionKind>, 4> kConditionKinds{{{"fixed", ConditionKind::Fixed},
                                                               {"slip", ConditionKind::Slip},
                                                               {"velocity", ConditionKind::Velocity},
                                                               {"moving_wall", ConditionKind::MovingWall}}};
constexpr std::array<Named<bool>, 2> kMaterialSides{{{"below", true}, {"above", false}}};
constexpr std::array<Named<int>, 6> kFaces{
    {{"x-", 0}, {"x+", 1}, {"y-", 2}, {"y+", 3}, {"z-", 4}, {"z+", 5}}};  // axis = id / 2, side = id % 2
constexpr std::array<Named<int>, 3> kAxes{{{"x", 0}, {"y", 1}, {"z", 2}}};
constexpr std::array<Named<UpdateScheme>, 6> kSchemes{{{"usl", UpdateScheme::USL},
                                                       {"usf", UpdateScheme::USF},
                                                       {"musl", UpdateScheme::MUSL},
                                                       {"usl+", UpdateScheme::MUSL},
                                                       {"usavg", UpdateScheme::USAVG},
                                                       {"usavg+", UpdateScheme::USAVGPlus}}};
constexpr std::array<Named<VelocityTransfer>, 5> kTransfers{{{"flip", VelocityTransfer::FLIP},
                                                             {"pic", VelocityTransfer::PIC},
                                                             {"blend", VelocityTransfer::Blend},
                                                             {"fmpm", VelocityTransfer::FMPM},
                                                             {"xpic", VelocityTransfer::XPIC}}};
constexpr std::array<Named<FmpmMeasure>, 2> kFmpmMeasures{
    {{"means", FmpmMeasure::Means}, {"changes", FmpmMeasure::Changes}}};
constexpr std::array<Named<FmpmBoundaryMethod>, 2> kFmpmBoundaryMethods{
    {{"incremental", FmpmBoundaryMethod::Incremental}, {"combined", FmpmBoundaryMethod::Combined}}};
constexpr std::array<Named<FmpmRecursion>, 2> kFmpmRecursions{
    {{"incremental", FmpmRecursion::Incremental}, {"binomial", FmpmRecursion::Binomial}}};
constexpr int kMaxFmpmOrder = 1000;
constexpr std::array<Named<ShapeKind>, 9> kShapeKinds{{{"linear", ShapeKind::Linear},
                                                       {"bspline2", ShapeKind::BSpline2},
                                                       {"bspline3", ShapeKind::BSpline3},
                                                       {"ugimp", ShapeKind::UGIMP},
                                                       {"cpgimp", ShapeKind::CpGIMP},
                                                       {"cpdi1", ShapeKind::CPDI1},
                                                       {"cpdi2", ShapeKind::CPDI2},
                                                       {"b2gimp", ShapeKind::B2GIMP},
                                                       {"b2cpdi", ShapeKind::B2CPDI}}};
constexpr std::array<Named<Mapping>, 3> kMappings{
    {{"mpm", Mapping::MPM}, {"impm", Mapping::IMPM}, {"mls_velocity", Mapping::MlsVelocity}}};
constexpr std::array<Named<CellQuadrature>, 2> kCellQuadratures{
    {{"cell_centre", CellQuadrature::Centre}, {"gauss_2x2", CellQuadrature::Gauss2}}};
constexpr std::array<Named<CellVolume>, 2> kCellVolumes{
    {{"cell", CellVolume::Full}, {"particle_fraction", CellVolume::ParticleFraction}}};
constexpr std::array<Named<DeformationUpdate>, 2> kDeformationUpdates{
    {{"exponential", DeformationUpdate::Exponential}, {"linear", DeformationUpdate::Linear}}};

constexpr std::array<Named<MeshElement>, 5> kMeshElements{{{"q4", MeshElement::Q4},
                                                           {"q9", MeshElement::Q9},
                                                           {"t3", MeshElement::T3},
                                                           {"hex8", MeshElement::Hex8},
                                                           {"bspline2", MeshElement::BSpline2}}};
constexpr std::array<Named<mesh::TrianglePattern>, 4> kTrianglePatterns{
    {{"rising", mesh::TrianglePattern::Rising},
     {"falling", mesh::TrianglePattern::Falling},
     {"alternating", mesh::TrianglePattern::Alternating},
     {"crossed", mesh::TrianglePattern::Crossed}}};
constexpr std::array<Named<SolverKind>, 3> kSolverKinds{{{"explicit", SolverKind::Explicit},
                                                         {"implicit_mpm", SolverKind::ImplicitMpm},
                                                         {"implicit_ul", SolverKind::ImplicitUl}}};
constexpr std::array<Named<LinearSolverChoice>, 5> kLinearSolvers{{{"umfpack", LinearSolverChoice::Umfpack},
                                                                   {"klu", LinearSolverChoice::Klu},
                                                                   {"bicgstab", LinearSolverChoice::BiCgStab},
                                                                   {"gmres", LinearSolverChoice::Gmres},
                                                                   {"petsc", LinearSolverChoice::Petsc}}};
constexpr std::array<Named<SoftStiffnessRule>, 2> kFlagRules{
    {{"paper", SoftStiffnessRule::Paper}, {"code", SoftStiffnessRule::Code}}};
constexpr std::array<Named<ImplicitBasis>, 3> kImplicitBases{
    {{"mesh", ImplicitBasis::Mesh}, {"mls", ImplicitBasis::Mls}, {"lme", ImplicitBasis::Lme}}};
constexpr std::array<Named<bool>, 2> kInitialAccelerations{{{"zero", false}, {"body_force", true}}};
/// solver.meshfree.mls_weight: the Gaussian less its tangent at R (C1, the default) or cut off at R (the
/// authors' code; shape/meshfree_mls.hpp). The value is "truncated".
constexpr std::array<Named<bool>, 2> kMlsWeights{{{"smooth", false}, {"truncated", true}}};
/// solver.meshfree.node_history: each step starts from the nodes' v and a projected from the
/// particles' (the default, implicit/meshfree/meshfree_stepper.hpp) or carried by the nodes (the
/// paper's Algorithm 2). The value is "carried".
constexpr std::array<Named<bool>, 2> kNodeHistories{{{"projected", false}, {"carried", true}}};

/// fe_bodies[].inertia: the physical inertia rho (default) or the authors' code's unit density
/// (Aulisa & Capodaglio, extraction A2).
constexpr std::array<Named<bool>, 2> kFeInertia{{{"physical", false}, {"unit_density", true}}};
constexpr std::array<Named<HeatTransfer>, 2> kHeatTransfers{
    {{"flip", HeatTransfer::FLIP}, {"fmpm", HeatTransfer::FMPM}}};  // heat.transfer
constexpr std::array<Named<ThermalContact>, 3> kThermalContacts{{{"perfect", ThermalContact::Perfect},
                                                                 {"conductance", ThermalContact::Conductance},
                                                                 {"insulated", ThermalContact::Insulated}}};

}  // namespace matpoint::input_detail
