// The DEM engine: spheres in a periodic box deformed by a homogeneous,
// diagonal velocity gradient; linear Cundall–Strack contacts; leapfrog time
// integration with Cundall's local damping of the fluctuating motion.
//
// Kinematics (SPEC §4). Positions are stored scaled by the cell sides,
// x = H s with H = diag(L); a particle's velocity is its fluctuation v plus
// the affine field D x, so that ds/dt = H⁻¹ v and the cell follows
// dH/dt = D H, integrated exactly over each step (H ← exp(Δt D) H). The affine motion carries no inertia (the usual choice for
// periodic cells); Newton's law and damping act on the fluctuation:
//   a = F/m,  a_k ← a_k (1 − χ sign(a_k (v_k + a_k Δt/2))),  v ← v + Δt a,
//   s ← s + Δt H⁻¹ v, and the same for spins with torques (no orientation is
// kept: spheres). Contacts see the image velocity D l of the branch vector.
//
// Features a scene does not use are compiled out: the pair loop and the
// integrator are instantiated for every combination of friction (shear
// history, torques, spins), damping, stress summation and stiffness summation,
// and one of them is chosen per step.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/state_measures.h"
#include "dem/contact_law.h"
#include "dem/neighbor_list.h"
#include "dem/packing.h"
#include "dem/vec.h"

namespace granasym::dem {

struct Material {
  double youngs_modulus = 500e6;  // E (Pa)
  double stiffness_ratio = 0.3;   // ν = k_s/k_n
  double friction_angle = 0.5;    // φ (rad); μ = tan φ
  double density = 2650.0;        // ρ_s (kg/m³)
  double local_damping = 0.5;     // χ in [0, 1)
  bool IsValid(std::string* why) const;
  LinearCundallStrack::Params ContactParams() const;
  bool has_friction() const { return friction_angle > 0 && stiffness_ratio > 0; }
};

// Contact durations of an undamped pair t_c = π / sqrt(k_n/m) (paper Eq. 3),
// for the smallest and largest spheres, with both mass conventions of SPEC §4.
struct ContactDurations {
  double smallest_reduced_mass = 0;  // m_12 = m_i m_j/(m_i + m_j), two smallest spheres (s)
  double largest_reduced_mass = 0;
  double smallest_single_mass = 0;   // m_12 = m (the paper's quoted values)
  double largest_single_mass = 0;
  // Stability limit of the leapfrog scheme for the stiffest pair, 2/ω_max,
  // ω_max² = k_n (1/m_i + 1/m_j) max(1, 3.5 ν) (the factor 3.5 = 1 + r²m/I
  // couples sliding with rolling) (s).
  double critical_time_step = 0;
};
ContactDurations ComputeContactDurations(const std::vector<double>& radii,
                                         const Material& material);

class Engine {
 public:
  struct Options {
    double time_step = 1.2e-7;  // Δt (s)
    // Verlet skin as a fraction of the smallest diameter: larger skins
    // rebuild less often but list more non-touching pairs.
    double skin_fraction = 0.3;
    int threads = 1;  // OpenMP threads; results are bit-identical for a given count
    bool IsValid(std::string* why) const;
  };

  // What the next force evaluation should also sum.
  struct Request {
    bool stress = false;     // Love–Weber stress and contact-force statistics
    bool stiffness = false;  // affine (Voigt) stiffness for stress controllers
  };

  // Sums from the last force evaluation that asked for them.
  struct Sums {
    SymTensor stress{};   // σ, compression positive, Voigt order (Pa)
    // Affine stiffness dσ_aa/dε_bb (compression positive) for a, b in 1..3,
    // Voigt-like order 11, 22, 33, 12, 13, 23 of the index pair (a, b) (Pa).
    std::array<double, 6> stiffness{};
    int64_t contacts = 0;
    double force_sum = 0;  // Σ |F_c| over contacts (N)
  };

  Engine(const Packing& packing, const Material& material, const Options& options);

  // Sets the diagonal velocity gradient D (continuum sign, extension
  // positive, 1/s) used from the next step on.
  void SetVelocityGradient(const std::array<double, 3>& gradient) { gradient_ = gradient; }
  const std::array<double, 3>& velocity_gradient() const { return gradient_; }

  // Evaluates contact forces at the current positions (rebuilding the
  // neighbour list when needed). Leaves net forces and torques in place.
  // Calling it again before Integrate() gives the same forces (the shear
  // history advances once per step), with the sums now requested.
  void ComputeForces(Request request);
  // Advances velocities, positions and the cell by one step.
  void Integrate();
  // ComputeForces + Integrate.
  void Step(Request request);
  void Step();

  const Sums& sums() const { return sums_; }
  size_t size() const { return position_.size(); }
  const std::array<double, 3>& cell() const { return cell_; }
  double volume() const { return cell_[0] * cell_[1] * cell_[2]; }
  double solid_volume() const { return solid_volume_; }
  double void_ratio() const { return volume() / solid_volume_ - 1.0; }
  double time() const { return time_; }
  int64_t step() const { return step_; }
  double time_step() const { return options_.time_step; }
  const Material& material() const { return material_; }
  const Options& options() const { return options_; }
  const NeighborList& neighbors() const { return neighbors_; }

  // Particle data (SoA): scaled positions with radius in w, fluctuating
  // velocities with inverse mass in w, spins with inverse inertia in w, and
  // net forces/torques of the last evaluation.
  const std::vector<Vec4>& scaled_positions() const { return position_; }
  const std::vector<Vec4>& velocities() const { return velocity_; }
  const std::vector<Vec4>& spins() const { return spin_; }
  const std::vector<Vec4>& forces() const { return force_; }
  const std::vector<int64_t>& ids() const { return id_; }
  Vec3 Position(size_t i) const {
    return {cell_[0] * position_[i].x, cell_[1] * position_[i].y, cell_[2] * position_[i].z};
  }
  // For tests and initial conditions.
  void SetVelocity(size_t i, Vec3 velocity);
  void SetSpin(size_t i, Vec3 spin);

  // The current packing (positions wrapped into the cell), in input order.
  Packing CurrentPacking() const;

  // Full state for checkpoints; Restore continues bit-identically.
  struct State {
    std::vector<Vec4> position, velocity, spin;
    std::vector<int64_t> id;
    std::array<double, 3> cell{}, gradient{};
    double time = 0;
    int64_t step = 0;
    double max_displacement = 0;
    bool forces_current = false;
    NeighborList::State neighbors;
  };
  State Save() const;
  void Restore(State state);

 private:
  template <unsigned kFlags>
  void ComputeForcesImpl();
  template <unsigned kFlags>
  void IntegrateImpl();

  Material material_;
  Options options_;
  LinearCundallStrack law_;
  std::array<double, 3> cell_{};
  std::array<double, 3> gradient_{};
  double time_ = 0;
  int64_t step_ = 0;
  double solid_volume_ = 0;
  double skin_ = 0;
  // Upper bound of the largest displacement since the last list build (m).
  double max_displacement_ = 0;
  bool forces_current_ = false;  // forces evaluated at the current positions
  bool friction_ = false;
  bool damping_ = false;

  std::vector<Vec4> position_, velocity_, spin_, force_, torque_;
  std::vector<int64_t> id_;
  // Forces and torques of threads 1..T−1 (thread 0 writes force_/torque_).
  std::vector<std::vector<Vec4>> thread_force_, thread_torque_;
  std::vector<Sums> thread_sums_;
  // Per-thread scratch of the pair loop: a block of touching pairs.
  struct ContactBlock {
    static constexpr int kSize = LinearCundallStrack::Batch::kSize;
    int32_t i[kSize], j[kSize];
    int64_t pair[kSize];
    LinearCundallStrack::Batch batch;
  };
  std::vector<ContactBlock> blocks_;
  NeighborList neighbors_;
  Sums sums_;
};

}  // namespace granasym::dem
