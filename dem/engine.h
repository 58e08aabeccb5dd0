// The DEM engine: spheres in a periodic box deformed by a homogeneous,
// diagonal velocity gradient; pairwise contact laws (material.h: linear
// Cundall–Strack by default, Hertz–Mindlin, optional rolling resistance);
// leapfrog time integration with Cundall's local damping of the fluctuating
// motion.
//
// Kinematics (SPEC §4). Positions are stored scaled by the cell sides,
// x = H s with H = diag(L); a particle's velocity is its fluctuation v plus
// the affine field D x, so that ds/dt = H⁻¹ v and the cell follows
// dH/dt = D H, integrated exactly over each step (H ← exp(Δt D) H). The
// affine motion carries no inertia (the usual choice for periodic cells);
// Newton's law and damping act on the fluctuation:
//   a = F/m,  a_k ← a_k (1 − χ sign(a_k (v_k + a_k Δt/2))),  v ← v + Δt a,
//   s ← s + Δt H⁻¹ v, and the same for spins with torques (no orientation is
// kept: spheres). Contacts see the image velocity D l of the branch vector.
//
// Features a scene does not use are compiled out: the pair loop is a template
// on the contact law (contact_law.h) and is instantiated for every reachable
// combination of friction (shear history, torques, spins), stress summation,
// stiffness summation and re-evaluation at unchanged positions; the
// integrator for friction and damping; one of each is chosen per step.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "common/state_measures.h"
#include "dem/contact_law.h"
#include "dem/contact_laws.h"
#include "dem/material.h"
#include "dem/near_list.h"
#include "dem/neighbor_list.h"
#include "dem/packing.h"
#include "dem/vec.h"

namespace granasym::dem {

class Engine {
 public:
  struct Options {
    double time_step = 1.2e-7;  // Δt (s)
    // Verlet skin as a fraction of the smallest diameter: larger skins
    // rebuild less often but list more non-touching pairs.
    double skin_fraction = 0.3;
    // Skin of the near list (near_list.h) at its first build, as a fraction
    // of the Verlet skin: the force pass walks only the listed pairs within
    // it. Each later build adapts it to the cheapest step
    // (NearList::CheapestSkin). Speed only: the results do not depend on it.
    double near_skin_ratio = 0.25;
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
    SymTensor stress{};  // σ, compression positive, Voigt order (Pa)
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
  // Sets Δt (s, > 0) of the next Integrate() and of the contact law (whose
  // shear increment k_t Δt v_t is the tangential displacement of the step
  // just integrated). Call it between ComputeForces() and Integrate(), as the
  // run loop does: the step then moves by the new Δt and the next evaluation
  // increments the shear by the same displacement. Rebuilds the law; the
  // particle data, the list and the shear history are unchanged.
  void SetTimeStep(double time_step);
  // The shortest undamped duration π sqrt(m_12/k_n) of the pairs touching at
  // the current positions, with k_n = dF_n/du_N the law's tangent stiffness
  // at the pair's overlap (NormalStiffness) and m_12 = 1/(1/m_i + 1/m_j) from
  // the particles' inverse masses (s); +infinity when no pair touches (or
  // none has a stiffness, e.g. two held spheres). For the linear law the
  // durations do not depend on the overlap; for Hertz–Mindlin they shrink as
  // u_N^(-1/4). Needs the neighbour list of the current positions: call it
  // after ComputeForces() (before Integrate()).
  double SmallestContactDuration() const;
  // ComputeForces + Integrate, bit-identical to calling the two, in one pass
  // over the particles: each is advanced as soon as its net force is complete.
  // The sums requested are those of the forces before the step; forces()
  // likewise.
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
  const NearList& near_pairs() const { return near_; }

  // Particle data (SoA): scaled positions with radius in w, fluctuating
  // velocities with inverse mass in w, spins with inverse inertia in w, and
  // net forces/torques of the last evaluation.
  const std::vector<Vec4>& scaled_positions() const { return position_; }
  const std::vector<Vec4>& velocities() const { return velocity_; }
  const std::vector<Vec4>& spins() const { return spin_; }
  const std::vector<Vec4>& forces() const { return force_; }
  // Empty without friction (no torques are summed).
  const std::vector<Vec4>& torques() const { return torque_; }
  const std::vector<int64_t>& ids() const { return id_; }
  Vec3 Position(size_t i) const {
    return {cell_[0] * position_[i].x, cell_[1] * position_[i].y, cell_[2] * position_[i].z};
  }
  // For tests and initial conditions.
  void SetVelocity(size_t i, Vec3 velocity);
  void SetSpin(size_t i, Vec3 spin);
  // Overrides the inverse mass (1/kg) and inverse moment of inertia
  // (1/(kg m²)) of sphere i; 0 holds its centre or its spin fixed (they are
  // the w of velocities() and spins(), so Save/Restore carry them).
  void SetInverseMassAndInertia(size_t i, double inverse_mass, double inverse_inertia);

  // The current packing (positions wrapped into the cell), in input order.
  Packing CurrentPacking() const;

  // Full state for checkpoints; Restore continues bit-identically.
  struct State {
    std::vector<Vec4> position, velocity, spin;
    std::vector<int64_t> id;
    std::array<double, 3> cell{}, gradient{};
    double time = 0;
    int64_t step = 0;
    // Δt of the next step (s); 0 (a state saved before Δt was stored) keeps
    // the engine's own on Restore.
    double time_step = 0;
    double max_displacement = 0;
    bool forces_current = false;
    NeighborList::State neighbors;
  };
  State Save() const;
  void Restore(State state);

 private:
  // The contact laws a material can select (contact_laws.h).
  using Law = AnyContactLaw;
  static Law MakeLaw(const Material& material, double time_step);

  // Rebuilds the neighbour list and the near list when the displacements
  // call for it.
  void PrepareList();
  // Forces (and with `advance` the step's kick and drift in the same pass).
  void Evaluate(Request request, bool advance);
  // Calls the kernel instantiated for (friction, flags); kFlags lists every flag set.
  template <class PairLaw, unsigned... kFlags>
  void RunKernel(const PairLaw& law, bool friction, unsigned flags,
                 std::integer_sequence<unsigned, kFlags...>);
  template <class PairLaw, bool kUseFriction, unsigned kFlags>
  void ComputeForcesImpl(const PairLaw& law);
  template <unsigned kFlags>
  void IntegrateImpl();
  // The end of a step once every particle has moved: the displacement
  // bound (from the largest |v|²), the cell, time and step count.
  void FinishAdvance(double max_speed2);
  // Recomputes loaded_ from the list's history (after a build or a restore).
  void DeriveLoadedFlags();

  Material material_;
  Options options_;
  Law law_;
  std::array<double, 3> cell_{};
  std::array<double, 3> gradient_{};
  double time_ = 0;
  int64_t step_ = 0;
  double solid_volume_ = 0;
  double skin_ = 0;
  // Upper bound of the largest displacement since the last list build (m).
  double max_displacement_ = 0;
  double near_skin_ = 0;
  // The same bound since the last near-list build (m), and its step.
  double near_displacement_ = 0;
  int64_t near_build_step_ = 0;
  int64_t near_measurements_ = 0;  // exact displacement passes since then
  bool forces_current_ = false;    // forces evaluated at the current positions
  bool friction_ = false;
  bool damping_ = false;

  std::vector<Vec4> position_, velocity_, spin_, force_, torque_;
  std::vector<int64_t> id_;
  // Halos of threads 0..T−2: the forces and torques each sums on particles
  // past its own (zero between evaluations; force_/torque_ hold each
  // thread's own particles).
  std::vector<std::vector<Vec4>> thread_force_, thread_torque_;
  std::vector<Sums> thread_sums_;
  std::vector<double> thread_max2_;  // per thread: the largest |v|² it advanced
  // Per-thread scratch of the pair loop: a block of touching pairs, each
  // named by its place in the block of the near list (block start + offset
  // is its index there, where its pair index, i and j are read back).
  struct ContactBlock {
    static constexpr int kSize = ContactBatch::kSize;
    static_assert(kSize <= 256, "offsets in a block are bytes");
    uint8_t offset[kSize];
    ContactBatch batch;
  };
  std::vector<ContactBlock> blocks_;
  NeighborList neighbors_;
  // The pairs the force pass walks (derived state, not saved).
  NearList near_;
  // Per listed pair (with friction): 1 when the pair may hold a shear force
  // or rolling moment, i.e. it touched at its last evaluation or carried a
  // history into the list; derived state, not saved.
  std::vector<uint8_t> loaded_;
  Sums sums_;
};

}  // namespace granasym::dem
