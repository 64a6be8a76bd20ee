// Boundary-integrated interaction of a uniformly magnetized TARGET with the field of a
// uniformly magnetized polyhedral SOURCE (paper Sec. 4.2, Eqs. 16-18).
//
// Everything is in the SOURCE's frame: the caller transforms the target's samples
// (points, normals; SurfaceQuadrature's transformSamples) and its magnetization M_t and
// centre of mass r_c into it, and rotates the results back to the world.
//
// overlap: amperian (energy / current model; B of the source, including mu0 M_s inside)
//   F   = sum_k w_k (M_t . B_k) n_k                               (Eq. 16)
//   T   = M_t x sum_k w_k (n_k x A_k)        = M_t x int_Vt B dV   (Eq. 17)
//   Tm  = sum_k w_k (M_t . B_k) (r_k - r_c) x n_k                 (Eq. 18)
//   U   = -M_t . sum_k w_k (n_k x A_k)       = -int_Vt M_t . B dV
//   F = -grad U and T + Tm = -dU/dtheta; continuous through contact at faces without
//   surface current (pole faces; at side faces see exterior). In overlap it pulls
//   the bodies towards full overlap (the energy minimum).
// overlap: charge (Coulomb / surface-charge model, what Akoun-Yonnet gives; default)
//   B is replaced by mu0 H = B - mu0 M_s insideFraction on the samples:
//   F   = sum_k w_k (M_t . mu0 H_k) n_k      = int_dVt (M_t . n) mu0 H dA
//   Tm  = sum_k w_k (M_t . mu0 H_k) (r_k - r_c) x n_k
//   T   = mu0 M_t x int_Vt H dV = -mu0 M_t x sum_k w_k phi_k n_k    (phi: H = -grad phi)
//   U   = -mu0 int_Vt M_t . H dV = mu0 sum_k w_k (M_t . n_k) phi_k
//   Derivation of T: the charge model's complete torque is that of the target's surface
//   charge, int (M_t . n)(r - r_c) x mu0 H dA. Since curl H = 0 (also across the source's
//   boundary: tangential H is continuous) (M_t . grad) H = grad(M_t . H), and the
//   divergence theorem splits it exactly as T + Tm above, like Eqs. 17-18 with B -> mu0 H
//   - but int_Vt H dV cannot come from n x A (A belongs to B); it is -int dVt phi n dA,
//   phi = M_s . sum_p W_p n_p / (4 pi) continuous. (Adding mu0 M_t x int H dV to the
//   surface-charge torque would count the couple twice.)
//   U_charge = U_amperian + mu0 (M_t . M_s) V_overlap, F = -grad U_charge; the force jumps
//   by mu0 (M_t . M_s) grad V_overlap at contact and pushes overlapping bodies apart.
// overlap: exterior (the field outside the source continued into it; for contact solvers)
//   On a sample inside the source only the TANGENTIAL part of mu0 M_s is removed from B,
//   across the source face nearest to the sample (normal n_s, plane offset o_s):
//   B_ext = B - mu0 f (M_s - (M_s . n_s) n_s) = mu0 H + mu0 f (M_s . n_s) n_s.
//   Across a face B_n is continuous and B_t jumps by mu0 M_s x n_s, so B_ext is the field
//   just outside that face: a body sunk a little into another feels the force it felt
//   touching it, at every face. Amperian is continuous only where the contact face
//   carries no surface current (M_s parallel to n_s), charge only where it carries no
//   charge (M_s perpendicular to n_s); the other jumps by mu0 (M_t . M_s) times the contact
//   area, which a contact solver's penetration turns into kinetic energy.
//   T and U: the charge model's split plus the normal part over the overlap volume,
//   int_Vt B_ext dV = mu0 int_Vt H dV + mu0 sum_k w_k f_k (n_s . r_k - o_s)(n_s . n_k) (M_s . n_s) n_s
//   (div X = 1 with X = ((r - r_face) . n_s) n_s, zero on the face's plane), every term a
//   sample's own, so blocks of samples add up. Exact for overlap across one face, where
//   F = -grad U with U = U_charge - mu0 (M_t . n_s)(M_s . n_s) V_overlap; across an edge an
//   approximation of the order of the overlap (docs/physics.md#overlap-models).
// All models agree while the bodies do not overlap.
//
// form: surfaceCharge (charge and exterior only; docs/physics.md#force-form)
//   The same integrals as the target's surface charge sigma = M_t . n in the field the
//   model puts on the samples (mu0 H, or B_ext):
//   F   = sum_k w_k (M_t . n_k) field_k
//   T + Tm = sum_k w_k (M_t . n_k) (r_k - r_c) x field_k      (T as above, Tm the rest)
//   U   = sum_k w_k (M_t . n_k) mu0 (phi_k + f_k psi_k),  psi = -(M_s . n_s)(n_s . r - o_s)
//   (psi: exterior only, the potential of the normal part it adds inside the source;
//   zero on the face's plane, so U is continuous). For samples that move rigidly with
//   the target, F = -grad U and T + Tm = -dU/dtheta hold for ANY rule, however coarse,
//   because field = -mu0 grad(phi + f psi); the split form (Eqs. 16-18) holds them only
//   to the rule's accuracy: with one sample per triangle at a contact its force is
//   not a gradient, and the bodies gain or lose energy there. Both forms converge to
//   the same wrench as the rule is refined.
#pragma once

#include "PolyhedronField.hpp"

#include <magFoam/Wrench.hpp>

#include <span>
#include <string_view>

namespace mag::mbm {

/// How the source's field acts on target samples inside the source
/// (docs/physics.md#overlap-models).
enum class OverlapModel {
    charge,  ///< mu0 H (Akoun-Yonnet, pushes overlapping bodies apart); the default
    amperian, ///< B (energy-conserving current model, continuous at pole-face contact)
    exterior  ///< B less the tangential mu0 M_s across the nearest source face (continuous at any face)
};

/// Parses "charge", "amperian" or "exterior"; throws std::invalid_argument listing the valid names.
OverlapModel overlapModelFromName(std::string_view name);

/// How the boundary integrals are written (see the file comment).
enum class ForceForm {
    split,        ///< Eqs. 16-18: (M_t . field) n, torque = couple + mechanical; the default
    surfaceCharge ///< (M_t . n) field: the exact gradient of the sampled energy (charge, exterior)
};

/// Parses "split" or "surfaceCharge"; throws std::invalid_argument listing the valid names.
ForceForm forceFormFromName(std::string_view name);

/// Force and torques on the target (mag::Wrench), here in the source frame.
using mag::Wrench;

/// Force, magnetic torque, mechanical torque about rc and energy on the target.
/// source, Ms: the source's tables and magnetization (A/m, source frame);
/// points, weights, normals: the target's boundary samples in the source frame;
/// Mt, rc: the target's magnetization (A/m) and centre of mass (m), source frame.
/// form surfaceCharge with the amperian model throws std::invalid_argument.
Wrench interactionWrench(const PolyhedronTables& source, const Vec3& Ms,
                         std::span<const Vec3> points, std::span<const double> weights,
                         std::span<const Vec3> normals, const Vec3& Mt, const Vec3& rc,
                         OverlapModel model, ForceForm form = ForceForm::split);

/// The field integral of interactionWrench() per unit source magnetization: K with
/// Wrench::fieldIntegral = K Ms (source frame), for any Ms, from one pass of the
/// geometric outputs (S and the inside fraction; no B): the fieldIntegral of the
/// three unit magnetizations at the cost of less than one wrench. The integral
/// does not depend on M_t or on the form (split and surfaceCharge give the same
/// for charge and amperian; for exterior the overlap's normal part is summed as
/// each form sums it, which agree as the rule converges).
Mat3 fieldIntegralMap(const PolyhedronTables& source, std::span<const Vec3> points,
                      std::span<const double> weights, std::span<const Vec3> normals, OverlapModel model,
                      ForceForm form = ForceForm::split);

/// Energy-consistent quantities of the pair (both models at once, one field pass):
/// F_model = -grad U_model and (T + Tm)_model = -dU_model/dtheta.
struct InteractionEnergy {
    double amperian = 0.0;      ///< J, U = -int_Vt M_t . B dV
    double charge = 0.0;        ///< J, U = -mu0 int_Vt M_t . H dV = amperian + mu0 Mt.Ms V
    double overlapVolume = 0.0; ///< m^3, int_Vt insideFraction dV = sum w (S . n) / (4 pi)
    Vec3 integralB = Vec3::Zero(); ///< T m^3, int_Vt B dV = sum w n x A
    Vec3 integralH = Vec3::Zero(); ///< A m^2, int_Vt H dV = -sum w phi n
};

/// Interaction energies, overlap volume and volume integrals of B and H over the target
/// (arguments as interactionWrench).
InteractionEnergy interactionEnergy(const PolyhedronTables& source, const Vec3& Ms,
                                    std::span<const Vec3> points,
                                    std::span<const double> weights,
                                    std::span<const Vec3> normals, const Vec3& Mt);

} // namespace mag::mbm
