#include "dem/engine.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "common/error.h"
#include "dem/minimum_image.h"

namespace granasym::dem {
namespace {

// The near list's skin adapts within [this, 1] times the Verlet skin.
constexpr double kSmallestNearSkinRatio = 1.0 / 64;

// What a force kernel also does besides the forces (friction is a separate
// template parameter, see RunKernel).
// kAdvance: the kick and drift of each particle follow in the same pass, as
// soon as its net force is complete (Engine::Step).
enum ForceFlag : unsigned { kStress = 1, kStiffness = 2, kFrozen = 4, kAdvance = 8 };
// What the integrator does besides the translations.
enum IntegrateFlag : unsigned { kRotation = 1, kDamping = 2 };

// The integrator accumulates a cheap upper bound of a Verlet list's
// displacements, Σ Δt max_i |v_i|; only when that bound calls for a rebuild
// is the exact displacement measured (one pass over the particles) and put in
// its place. Returns whether it measured. For NeighborList and NearList.
template <class VerletList>
bool TightenDisplacement(const VerletList& list, const std::vector<Vec4>& positions,
                         const std::array<double, 3>& cell, int threads, double* displacement) {
  if (!list.NeedsRebuild(*displacement * list.MetricFactor(), cell)) return false;
  *displacement = list.MaxDisplacement(positions, cell, threads);
  return true;
}

// The leapfrog update works on whole Vec4s at once (GCC's vector extension:
// one 256-bit register per Vec4, two 128-bit halves where the CPU has no
// wider vectors). Each of x, y, z gets exactly the operations, in the same
// order, that it would get alone, so the results are those of the update
// one component at a time, bit for bit; the fourth component (inverse mass
// or inertia, radius) is carried unchanged.
using Lanes = double __attribute__((vector_size(32)));
using LaneMasks = int64_t __attribute__((vector_size(32)));
static_assert(sizeof(Lanes) == sizeof(Vec4) && alignof(Vec4) >= alignof(Lanes));

// Two doubles in one 128-bit register: the gather and scatter move the
// data of two contacts at once, a Vec4 as its halves (x, y) and (z, w).
using Pair = double __attribute__((vector_size(16)));
inline Pair LoadPair(const double* a) {
  Pair v;
  std::memcpy(&v, a, sizeof v);
  return v;
}
inline void StorePair(Pair v, double* a) { std::memcpy(a, &v, sizeof v); }
// (a[0], b[0]) and (a[1], b[1]): one unpack instruction each (GCC compiles
// the same built from elements into several).
#if defined(__clang__)
inline Pair Firsts(Pair a, Pair b) { return __builtin_shufflevector(a, b, 0, 2); }
inline Pair Seconds(Pair a, Pair b) { return __builtin_shufflevector(a, b, 1, 3); }
#else
using PairIndices = int64_t __attribute__((vector_size(16)));
inline Pair Firsts(Pair a, Pair b) { return __builtin_shuffle(a, b, PairIndices{0, 2}); }
inline Pair Seconds(Pair a, Pair b) { return __builtin_shuffle(a, b, PairIndices{1, 3}); }
#endif

// The halves of a Vec4 in a register, and two Vec4s' components interleaved
// by halves: Evens(a, b) = (a.x, b.x, a.z, b.z), Odds(a, b) = (a.y, b.y,
// a.w, b.w) (one unpack instruction each).
inline Pair Low(Lanes v) { return Pair{v[0], v[1]}; }
inline Pair High(Lanes v) { return Pair{v[2], v[3]}; }
#if defined(__clang__)
inline Lanes Evens(Lanes a, Lanes b) { return __builtin_shufflevector(a, b, 0, 4, 2, 6); }
inline Lanes Odds(Lanes a, Lanes b) { return __builtin_shufflevector(a, b, 1, 5, 3, 7); }
#else
inline Lanes Evens(Lanes a, Lanes b) { return __builtin_shuffle(a, b, LaneMasks{0, 4, 2, 6}); }
inline Lanes Odds(Lanes a, Lanes b) { return __builtin_shuffle(a, b, LaneMasks{1, 5, 3, 7}); }
#endif

inline Lanes LoadLanes(const Vec4& a) {
  Lanes v;
  std::memcpy(&v, &a, sizeof v);
  return v;
}
inline void StoreLanes(Lanes v, Vec4* a) { std::memcpy(static_cast<void*>(a), &v, sizeof v); }

// v ← v + Δt a with a = load · w (w = v.w: the inverse mass or inertia) and,
// with kDamping, Cundall's local damping of each component of the
// fluctuating acceleration: a_k ← a_k (1 − χ sign(a_k (v_k + a_k Δt/2))),
// sign(0) = sign(NaN) = 0.
template <bool kDamping>
inline Lanes Kick(Lanes load, Lanes v, double dt, double chi) {
  constexpr LaneMasks kXyz = {-1, -1, -1, 0};
  const Lanes w = {v[3], v[3], v[3], v[3]};
  // a's fourth component is 0, so v.w + Δt·0 keeps v.w.
  Lanes a = reinterpret_cast<Lanes>(reinterpret_cast<LaneMasks>(load * w) & kXyz);
  if constexpr (kDamping) {
    const Lanes t = a * (v + (0.5 * dt) * a);
    const LaneMasks plus = reinterpret_cast<LaneMasks>(Lanes{} + 1.0);
    const LaneMasks minus = reinterpret_cast<LaneMasks>(Lanes{} - 1.0);
    const Lanes sign = reinterpret_cast<Lanes>(((t > 0.0) & plus) | ((t < 0.0) & minus));
    a *= 1.0 - chi * sign;
  }
  return v + dt * a;
}

// Leapfrog update of particle i with its net force and torque: kick of the
// velocity (and spin), drift of the scaled position by Δt H⁻¹ v; returns |v|².
// The one update of both the separate (Integrate) and fused (Step) paths.
// `inverse_cell` is (1/L_x, 1/L_y, 1/L_z, 0).
template <bool kRotation, bool kDamping>
inline double AdvanceParticle(const Vec4& force, const Vec4& torque, double dt, double chi,
                              Lanes inverse_cell, Vec4* velocity, Vec4* spin, Vec4* position) {
  const Lanes v = Kick<kDamping>(LoadLanes(force), LoadLanes(*velocity), dt, chi);
  StoreLanes(v, velocity);
  StoreLanes(LoadLanes(*position) + dt * v * inverse_cell, position);
  if constexpr (kRotation) {
    StoreLanes(Kick<kDamping>(LoadLanes(torque), LoadLanes(*spin), dt, chi), spin);
  }
  const Lanes v2 = v * v;
  return v2[0] + v2[1] + v2[2];
}

// What the force pass will read and write of the sphere j of a pair, for
// CollectTouching to prefetch (a thread's j past `own_end` is summed in its
// halo). Null position: no prefetching; null velocity: the position only
// (no friction, no gather).
struct PrefetchTargets {
  const Vec4* position = nullptr;
  const Vec4* velocity = nullptr;
  const Vec4* spin = nullptr;
  const Vec4* force = nullptr;
  const Vec4* halo_force = nullptr;
  const Vec4* torque = nullptr;
  const Vec4* halo_torque = nullptr;
  int64_t own_end = 0;
};
// How many near pairs ahead CollectTouching prefetches (on Zen 5 the time
// was flat from 16 to 64 pairs), and from what size of the particle arrays
// the pass touches (position, velocity, spin, force, torque: 160 B per
// sphere) on: 1.6 MB (10 000 spheres) lost 2.5 %, 24 MB (150 000) gained
// 30 % (bench/README.md, seventh round). With more than one thread it
// always prefetches: the other threads' j come from another core's cache
// (10 000 spheres, 2 threads: 3 % faster).
constexpr int64_t kPrefetchAhead = 32;
constexpr double kPrefetchFromBytes = 8.0 * (1 << 20);

// Pass (1) of the pair loop over the near pairs [q0, q1) of one thread:
// each pair's branch vector, |l|² and radii to the next free slot of the
// batch and its offset in the block beside them, the slot kept only when
// the pair touches; returns the number of touching pairs. With kForget a
// pair that stopped touching forgets its history. A function of its own
// so that the compiler allocates the registers of this tight loop alone
// (inlined into the kernel, it kept the list's pointers on the stack).
// It also prefetches, kPrefetchAhead pairs ahead, the position of that
// pair's j and, with friction, the velocity, spin, force and torque that
// the gather and the scatter will touch: the particles i come in order (the
// hardware prefetchers follow them), the j do not; in a sample larger than
// the caches their misses were a third of a step (bench/README.md, seventh
// round).
template <bool kForget, bool kRolling>
__attribute__((noinline)) int CollectTouching(const NearList::Pairs& pairs, int64_t q0, int64_t q1,
                                              const Vec4* position, double lx, double ly, double lz,
                                              uint8_t* loaded, Vec3* shear, Vec3* rolling,
                                              uint8_t* offset, ContactBatch& batch,
                                              PrefetchTargets targets) {
  const int32_t* near_i = pairs.i.data();
  const int32_t* near_j = pairs.j.data();
  const int64_t* near_p = pairs.p.data();
  // Locals, which the one-byte stores below cannot alias.
  const int64_t last = pairs.size() - 1;
  const Lanes cell = {lx, ly, lz, 0.0};
  const Vec4* ahead_position = targets.position;
  const Vec4* velocity = targets.velocity;
  const Vec4* spin = targets.spin;
  const Vec4* force = targets.force;
  const Vec4* halo_force = targets.halo_force;
  const Vec4* torque = targets.torque;
  const Vec4* halo_torque = targets.halo_torque;
  const int64_t own_end = targets.own_end;
  int count = 0;
  for (int64_t q = q0; q < q1; ++q) {
    if (ahead_position != nullptr) {
      const int32_t ahead = near_j[std::min(q + kPrefetchAhead, last)];
      __builtin_prefetch(&ahead_position[ahead]);
      if (velocity != nullptr) {
        const bool own = ahead < own_end;
        __builtin_prefetch(&velocity[ahead]);
        __builtin_prefetch(&spin[ahead]);
        __builtin_prefetch(&(own ? force : halo_force)[ahead], 1);
        __builtin_prefetch(&(own ? torque : halo_torque)[ahead], 1);
      }
    }
    const int32_t i = near_i[q], j = near_j[q];
    // Branch(position[i], position[j]) and its Dot on whole Vec4s: x, y and
    // z each get Branch's operations, and |l|² is summed in Dot's order
    // ((x² + y²) + z²), so both are bit for bit those of the scalar code;
    // the fourth lane (radius difference, times 0) is not used.
    const Lanes l = cell * MinimumImage(LoadLanes(position[j]) - LoadLanes(position[i]));
    const Lanes l2 = l * l;
    const double distance2 = (l2[0] + l2[1]) + l2[2];
    const double ri = position[i].w, rj = position[j].w;
    const double reach = ri + rj;
    const bool touching = distance2 < reach * reach;
    offset[count] = static_cast<uint8_t>(q - q0);
    batch.bx[count] = l[0];
    batch.by[count] = l[1];
    batch.bz[count] = l[2];
    batch.d2[count] = distance2;
    batch.ri[count] = ri;
    batch.rj[count] = rj;
    count += touching;
    if constexpr (kForget) {
      // A broken contact forgets its shear force (and rolling moment).
      // The one-byte flag of a pair that may hold a history, not the
      // 24-byte history itself, is what the many never-touching pairs
      // read; it is written only when it changes (a contact made or
      // broken: rare, so the branch is well predicted, never the coin
      // toss of `touching` itself).
      const int64_t p = near_p[q];
      if (loaded[p] != static_cast<uint8_t>(touching)) {
        if (!touching) {
          shear[p] = Vec3{};
          if constexpr (kRolling) rolling[p] = Vec3{};
        }
        loaded[p] = touching;
      }
    }
  }
  return count;
}

// Pass (2a): the stored shear forces, the centre velocities v_j + D l − v_i
// and the spins of the `count` touching pairs of the block at q0 into the
// batch (a function of its own, as CollectTouching). Two pairs at a time:
// each Vec4 read as two halves, the halves of two pairs interleaved into
// the batch's columns (one 128-bit store for two values). An odd last pair
// goes in both halves: its second copy lands in the unused slot `count`
// (count < kSize when odd).
template <bool kRolling>
__attribute__((noinline)) void GatherKinematics(const NearList::Pairs& pairs, int64_t q0,
                                                const uint8_t* offset, int count, const Vec3* shear,
                                                const Vec3* rolling, const Vec4* velocity,
                                                const Vec4* spin, double gx, double gy, double gz,
                                                ContactBatch& batch) {
  const int32_t* near_i = pairs.i.data();
  const int32_t* near_j = pairs.j.data();
  const int64_t* near_p = pairs.p.data();
  for (int k = 0; k < count; k += 2) {
    const int kb = k + 1 < count ? k + 1 : k;
    const int64_t qa = q0 + offset[k], qb = q0 + offset[kb];
    const int64_t pa = near_p[qa], pb = near_p[qb];
    const int32_t ia = near_i[qa], ja = near_j[qa], ib = near_i[qb], jb = near_j[qb];
    const Pair sa = LoadPair(&shear[pa].x), sb = LoadPair(&shear[pb].x);
    StorePair(Firsts(sa, sb), batch.sx + k);
    StorePair(Seconds(sa, sb), batch.sy + k);
    StorePair(Pair{shear[pa].z, shear[pb].z}, batch.sz + k);
    if constexpr (kRolling) {
      for (int u = 0; u < 2; ++u) {
        const Vec3 moment = rolling[u == 0 ? pa : pb];
        batch.rmx[k + u] = moment.x;
        batch.rmy[k + u] = moment.y;
        batch.rmz[k + u] = moment.z;
      }
    }
    // Velocities and spins as whole Vec4s (each component's difference is
    // the one it had alone; the fourth lanes are not used), the two
    // contacts' components interleaved by halves into the columns.
    const Lanes dv_a = LoadLanes(velocity[ja]) - LoadLanes(velocity[ia]);
    const Lanes dv_b = LoadLanes(velocity[jb]) - LoadLanes(velocity[ib]);
    const Lanes dv_xz = Evens(dv_a, dv_b), dv_yw = Odds(dv_a, dv_b);
    StorePair(Low(dv_xz) + gx * LoadPair(batch.bx + k), batch.vx + k);
    StorePair(Low(dv_yw) + gy * LoadPair(batch.by + k), batch.vy + k);
    StorePair(High(dv_xz) + gz * LoadPair(batch.bz + k), batch.vz + k);
    const Lanes wi_a = LoadLanes(spin[ia]), wi_b = LoadLanes(spin[ib]);
    const Lanes wj_a = LoadLanes(spin[ja]), wj_b = LoadLanes(spin[jb]);
    const Lanes wi_xz = Evens(wi_a, wi_b), wi_yw = Odds(wi_a, wi_b);
    const Lanes wj_xz = Evens(wj_a, wj_b), wj_yw = Odds(wj_a, wj_b);
    StorePair(Low(wi_xz), batch.wix + k);
    StorePair(Low(wi_yw), batch.wiy + k);
    StorePair(High(wi_xz), batch.wiz + k);
    StorePair(Low(wj_xz), batch.wjx + k);
    StorePair(Low(wj_yw), batch.wjy + k);
    StorePair(High(wj_xz), batch.wjz + k);
  }
}

}  // namespace

bool Engine::Options::IsValid(std::string* why) const {
  if (!(time_step > 0)) return *why = "time_step must be > 0", false;
  if (!(skin_fraction > 0 && skin_fraction <= 2))
    return *why = "skin_fraction must be in (0, 2]", false;
  if (!(near_skin_ratio > 0 && near_skin_ratio <= 1))
    return *why = "near_skin_ratio must be in (0, 1]", false;
  if (threads < 1) return *why = "threads must be >= 1", false;
  return true;
}

Engine::Law Engine::MakeLaw(const Material& material, double time_step) {
  return VisitContactLaw(material, [&](auto law) -> Law {
    using PairLaw = typename decltype(law)::type;
    return PairLaw(PairLaw::Params::FromMaterial(material), time_step);
  });
}

Engine::Engine(const Packing& packing, const Material& material, const Options& options)
    : material_(material),
      options_(options),
      law_(MakeLaw(material, options.time_step)),
      cell_(packing.cell) {
  std::string why;
  if (!material.IsValid(&why)) throw InputError("material: " + why);
  if (!options.IsValid(&why)) throw InputError("engine options: " + why);
  GRANASYM_CHECK(packing.size() > 0) << "empty packing";
  GRANASYM_CHECK(packing.size() < (size_t{1} << 31)) << "too many particles for 32-bit indices";
  friction_ = material.has_friction();
  damping_ = material.local_damping > 0;
  neighbors_.set_track_shear(friction_);
  neighbors_.set_track_rolling(material.has_rolling_resistance());
  const size_t n = packing.size();
  const double min_radius = *std::min_element(packing.radii.begin(), packing.radii.end());
  skin_ = options.skin_fraction * 2.0 * min_radius;
  near_skin_ = options.near_skin_ratio * skin_;

  // Order particles along the bins of the first neighbour-list build so that
  // neighbours are close in memory; ids keep the input order.
  const double max_radius = *std::max_element(packing.radii.begin(), packing.radii.end());
  std::array<int, 3> bins;
  for (int d = 0; d < 3; ++d) bins[d] = std::max(1, static_cast<int>(cell_[d] / (2 * max_radius)));
  std::vector<int64_t> bin(n);
  for (size_t i = 0; i < n; ++i) {
    int64_t index = 0;
    for (int d = 0; d < 3; ++d) {
      const double s = packing.positions[i][d] / cell_[d];
      index =
          index * bins[d] + std::min(bins[d] - 1, static_cast<int>((s - std::floor(s)) * bins[d]));
    }
    bin[i] = index;
  }
  std::vector<int64_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int64_t a, int64_t b) { return bin[a] < bin[b]; });

  position_.resize(n);
  velocity_.resize(n);
  spin_.resize(n);
  force_.resize(n);
  torque_.resize(n);
  id_.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const int64_t i = order[k];
    const double r = packing.radii[i];
    const double mass = SphereMass(r, material.density);
    Vec4& s = position_[k];
    s.x = packing.positions[i][0] / cell_[0];
    s.y = packing.positions[i][1] / cell_[1];
    s.z = packing.positions[i][2] / cell_[2];
    s.x -= std::floor(s.x);
    s.y -= std::floor(s.y);
    s.z -= std::floor(s.z);
    s.w = r;
    velocity_[k].w = 1.0 / mass;
    spin_[k].w = 1.0 / (0.4 * mass * r * r);
    id_[k] = i;
    solid_volume_ += 4.0 / 3.0 * kPi * r * r * r;
  }
  const int extra = options.threads - 1;
  thread_force_.assign(extra, std::vector<Vec4>(n));
  thread_torque_.assign(friction_ ? extra : 0, std::vector<Vec4>(n));
  thread_sums_.assign(options.threads, Sums{});
  thread_max2_.assign(options.threads, 0.0);
  blocks_.resize(options.threads);
}

void Engine::SetVelocity(size_t i, Vec3 v) {
  velocity_[i].x = v.x;
  velocity_[i].y = v.y;
  velocity_[i].z = v.z;
}

void Engine::SetSpin(size_t i, Vec3 w) {
  spin_[i].x = w.x;
  spin_[i].y = w.y;
  spin_[i].z = w.z;
}

void Engine::SetInverseMassAndInertia(size_t i, double inverse_mass, double inverse_inertia) {
  GRANASYM_CHECK(inverse_mass >= 0 && inverse_inertia >= 0);
  velocity_[i].w = inverse_mass;
  spin_[i].w = inverse_inertia;
}

// The pair loop, one function of some 340 lines on purpose: it is one OpenMP
// parallel region whose passes (collect, gather, the law, the scatter with
// the inline advance, then after the barrier the halo sums and the advance)
// share per-thread state the compiler keeps in registers: the loop's pointers
// as thread-private locals, sphere i's running sums over its contacts. What
// is inlined and what is not was measured pass by pass (bench/README.md, "DEM
// kernel: what was tried", rounds 3, 6, 8 and 10): the two helpers that ran
// faster out of line (CollectTouching, GatherKinematics) already are. A
// split would hand those decisions back to the compiler and have to be
// measured again; the tuning is finished.
template <class PairLaw, bool kUseFriction, unsigned kFlags>
void Engine::ComputeForcesImpl(const PairLaw& law) {
  constexpr bool kRolling = PairLaw::kRollingHistory;
  static_assert(kUseFriction || !kRolling, "rolling resistance needs friction");
  constexpr bool kSumStress = (kFlags & kStress) != 0;
  constexpr bool kSumStiffness = (kFlags & kStiffness) != 0;
  constexpr bool kReevaluate = (kFlags & kFrozen) != 0;
  constexpr bool kAdvanceToo = (kFlags & kAdvance) != 0;
  const int64_t n = static_cast<int64_t>(position_.size());
  const int threads = options_.threads;
  const double lx = cell_[0], ly = cell_[1], lz = cell_[2];
  const double gx = gradient_[0], gy = gradient_[1], gz = gradient_[2];
  Vec3* shear = kUseFriction ? neighbors_.shear().data() : nullptr;
  Vec3* rolling = kRolling ? neighbors_.rolling().data() : nullptr;
  uint8_t* loaded = kUseFriction ? loaded_.data() : nullptr;
  // With kAdvanceToo the kernel also writes these (a particle once its
  // force is complete, which no later pair reads: see below).
  Vec4* position = position_.data();
  Vec4* velocity = velocity_.data();
  Vec4* spin = spin_.data();
  const double dt = options_.time_step;
  const double chi = material_.local_damping;
  const bool damping = damping_;
  const Lanes inverse_cell = {1.0 / lx, 1.0 / ly, 1.0 / lz, 0.0};
  // Advances particles [from, to) with the net forces in force_/torque_.
  auto advance = [&](int64_t from, int64_t to, double& max2) {
    for (int64_t i = from; i < to; ++i) {
      const double v2 =
          damping
              ? AdvanceParticle<kUseFriction, true>(force_[i], torque_[i], dt, chi, inverse_cell,
                                                    &velocity[i], &spin[i], &position[i])
              : AdvanceParticle<kUseFriction, false>(force_[i], torque_[i], dt, chi, inverse_cell,
                                                     &velocity[i], &spin[i], &position[i]);
      max2 = std::max(max2, v2);
    }
  };

  // The loop's pointers and constants are private copies in each thread
  // (locals whose address is not taken): as shared variables they would be
  // read again from memory after each one-byte store of the passes, which
  // may alias anything.
#pragma omp parallel num_threads(threads) \
    firstprivate(lx, ly, lz, gx, gy, gz, shear, rolling, loaded, position, velocity, spin)
  {
    const int t = omp_get_thread_num();
    const int64_t begin = n * t / threads, end = n * (t + 1) / threads;
    // Pairs (i, j > i) of this thread touch only particles >= begin. Each
    // thread sums the forces on its own particles [begin, end) in force_
    // and torque_, which no other thread writes, and those on later
    // particles (j >= end) in its halo, which the threads owning them add
    // after the barrier and zero again: no thread writes another's
    // particles or zero-fills more than its own share.
    Vec4* force = force_.data();
    Vec4* torque = kUseFriction ? torque_.data() : nullptr;
    Vec4* halo_force = t + 1 < threads ? thread_force_[t].data() : nullptr;
    Vec4* halo_torque = kUseFriction && t + 1 < threads ? thread_torque_[t].data() : nullptr;
    std::fill(force + begin, force + end, Vec4{});
    if constexpr (kUseFriction) std::fill(torque + begin, torque + end, Vec4{});
    Sums local;
    double max2 = 0.0;  // largest |v|² of the particles this thread advanced
    // On one thread a particle's force is complete once the pairs of every
    // owner up to it are done (its pairs (m < i, i) come before (i, j > i)),
    // and no later pair reads it: it is advanced right there, while its data
    // are in cache. With more threads a particle may still receive forces
    // from another thread, so it is advanced after the barrier.
    const bool advance_inline = kAdvanceToo && threads == 1;
    int64_t advanced = 0;

    // Three passes over blocks of the near list. (1) CollectTouching: find the
    // touching pairs without a data-dependent branch (compaction by index
    // increment): the contact/no-contact decision is close to a coin toss in a
    // dense packing and would otherwise cost a branch misprediction per pair. Each
    // pair's branch vector, |l|² and radii go to the next free slot of the batch
    // and its offset in the block beside them; the slot is kept only when the pair
    // touches. (Stores bound these passes, one per cycle on some cores: the near
    // list keeps the pairs that do not touch few, which the whole neighbour list
    // did not.) (2) GatherKinematics: the rest of the touching pairs' kinematics
    // into the batch; the contact law on it in one vectorised loop. (3) Scatter
    // forces, torques and shear forces.
    ContactBlock& b = blocks_[t];
    ContactBatch& batch = b.batch;
    // The pairs walked are the near list's (the listed pairs that may touch,
    // in list order): q indexes them, near_p[q] is the pair in the list (its
    // history), near_i[q] and near_j[q] its spheres.
    const NearList::Pairs& near_pairs = near_.pairs(t);
    const int32_t* near_i = near_pairs.i.data();
    const int32_t* near_j = near_pairs.j.data();
    const int64_t* near_p = near_pairs.p.data();
    const int64_t near_end = near_pairs.size();
    // Friction and a fresh evaluation: the histories advance (a broken
    // contact forgets its own) and the kinematics are gathered.
    constexpr bool kGather = kUseFriction && !kReevaluate;
    PrefetchTargets prefetch;
    if (threads > 1 || 5.0 * sizeof(Vec4) * static_cast<double>(n) > kPrefetchFromBytes) {
      prefetch.position = position;
      if constexpr (kGather) {
        prefetch.velocity = velocity;
        prefetch.spin = spin;
        prefetch.force = force;
        prefetch.halo_force = halo_force;
        prefetch.torque = torque;
        prefetch.halo_torque = halo_torque;
        prefetch.own_end = end;
      }
    }
    constexpr int kBlock = ContactBatch::kSize;
    for (int64_t q0 = 0; q0 < near_end; q0 += kBlock) {
      const int64_t q1 = std::min<int64_t>(q0 + kBlock, near_end);
      const int count =
          CollectTouching<kGather, kRolling>(near_pairs, q0, q1, position, lx, ly, lz, loaded,
                                             shear, rolling, b.offset, batch, prefetch);
      if constexpr (kGather) {
        GatherKinematics<kRolling>(near_pairs, q0, b.offset, count, shear, rolling, velocity, spin,
                                   gx, gy, gz, batch);
      }
      if constexpr (kReevaluate) {
        // Forces again at unchanged positions (rare): the scalar evaluator
        // with the stored shear forces.
        for (int k = 0; k < count; ++k) {
          const int64_t p = near_p[q0 + b.offset[k]];
          ContactPair pair;
          pair.branch = {batch.bx[k], batch.by[k], batch.bz[k]};
          pair.distance = std::sqrt(batch.d2[k]);
          pair.radius_i = batch.ri[k];
          pair.radius_j = batch.rj[k];
          ContactHistory stored;
          if constexpr (kUseFriction) stored.shear = shear[p];
          if constexpr (kRolling) stored.rolling = rolling[p];
          const ContactResult r = law.template Evaluate<kUseFriction, true>(pair, stored);
          batch.fx[k] = r.force_i.x;
          batch.fy[k] = r.force_i.y;
          batch.fz[k] = r.force_i.z;
          batch.tix[k] = r.torque_i.x;
          batch.tiy[k] = r.torque_i.y;
          batch.tiz[k] = r.torque_i.z;
          batch.tjx[k] = r.torque_j.x;
          batch.tjy[k] = r.torque_j.y;
          batch.tjz[k] = r.torque_j.z;
        }
      } else {
        law.template EvaluateBatch<kUseFriction>(batch, count);
      }
      // Forces, torques and shear forces back to the particles and pairs,
      // two contacts at a time: the batch's columns read two values per
      // load, (x, y) of each added as one half of the Vec4 and z alone.
      // Each contact's sums are complete before the next's, in batch order:
      // every particle receives its terms in the order of one contact at a
      // time.
      auto add = [](Pair xy, double z, Vec4& to) {
        StorePair(LoadPair(&to.x) + xy, &to.x);
        to.z += z;
      };
      auto subtract = [](Pair xy, double z, Vec4& to) {
        StorePair(LoadPair(&to.x) - xy, &to.x);
        to.z -= z;
      };
      // The force and torque sums of sphere i over its run of contacts
      // (the pairs come in order of i) are kept in registers and stored
      // when the run or the block ends (the inline advance reads them):
      // each term is added in the same order as into memory, and no
      // contact after the run's first touches i's sums as its j (j > i).
      // It spares the reload of each partial sum through the store just
      // made (10 000 spheres, 1 thread: scatter −6 %, bench/README.md,
      // eighth round).
      int32_t run = -1;
      Pair run_f{}, run_t{};
      double run_fz = 0, run_tz = 0;
      auto flush = [&] {
        if (run < 0) return;
        StorePair(run_f, &force[run].x);
        force[run].z = run_fz;
        if constexpr (kUseFriction) {
          StorePair(run_t, &torque[run].x);
          torque[run].z = run_tz;
        }
      };
      auto scatter = [&](int k, Pair f_xy, Pair ti_xy, Pair tj_xy, Pair s_xy) {
        const int64_t q = q0 + b.offset[k];
        const int32_t i = near_i[q], j = near_j[q];
        // j's sums: this thread's own, or its halo (a select, not a branch).
        const bool own = j < end;
        if (i != run) {
          flush();
          run = i;
          run_f = LoadPair(&force[i].x);
          run_fz = force[i].z;
          if constexpr (kUseFriction) {
            run_t = LoadPair(&torque[i].x);
            run_tz = torque[i].z;
          }
        }
        run_f = run_f + f_xy;
        run_fz += batch.fz[k];
        subtract(f_xy, batch.fz[k], (own ? force : halo_force)[j]);
        if constexpr (kUseFriction) {
          if constexpr (!kReevaluate) {
            const int64_t p = near_p[q];
            StorePair(s_xy, &shear[p].x);
            shear[p].z = batch.sz[k];
            if constexpr (kRolling) rolling[p] = {batch.rmx[k], batch.rmy[k], batch.rmz[k]};
          }
          run_t = run_t + ti_xy;
          run_tz += batch.tiz[k];
          add(tj_xy, batch.tjz[k], (own ? torque : halo_torque)[j]);
        }
        const Vec3 f = {batch.fx[k], batch.fy[k], batch.fz[k]};  // on i
        const Vec3 branch = {batch.bx[k], batch.by[k], batch.bz[k]};
        const double distance2 = batch.d2[k];
        if constexpr (kSumStress) {
          // σ = (1/V) Σ F_j ⊗ l with F_j = −F_i the force on j (compression
          // positive for repulsion); symmetric part.
          const Vec3 fj = (-1.0) * f;  // on j
          local.stress[0] += fj.x * branch.x;
          local.stress[1] += fj.y * branch.y;
          local.stress[2] += fj.z * branch.z;
          local.stress[3] += 0.5 * (fj.x * branch.y + fj.y * branch.x);
          local.stress[4] += 0.5 * (fj.x * branch.z + fj.z * branch.x);
          local.stress[5] += 0.5 * (fj.y * branch.z + fj.z * branch.y);
          local.force_sum += Norm(fj);
          ++local.contacts;
        }
        if constexpr (kSumStiffness) {
          // Affine response of the normal force: dσ_aa/dε_bb = (1/V) Σ k_n l_a² l_b² / |l|²
          // with the tangent k_n (the rolling and shear springs are left out).
          const double weight =
              law.NormalStiffness(batch.ri[k], batch.rj[k], std::sqrt(distance2)) / distance2;
          const double xx = branch.x * branch.x, yy = branch.y * branch.y, zz = branch.z * branch.z;
          // Fused multiply-adds written out (the library compiles without
          // contraction); they keep the rounding these sums had.
          local.stiffness[0] = std::fma(weight * xx, xx, local.stiffness[0]);
          local.stiffness[1] = std::fma(weight * yy, yy, local.stiffness[1]);
          local.stiffness[2] = std::fma(weight * zz, zz, local.stiffness[2]);
          local.stiffness[3] = std::fma(weight * xx, yy, local.stiffness[3]);
          local.stiffness[4] = std::fma(weight * xx, zz, local.stiffness[4]);
          local.stiffness[5] = std::fma(weight * yy, zz, local.stiffness[5]);
        }
      };
      // An odd last contact reads slot `count` as its column partner
      // (count < kSize when odd) and scatters alone.
      for (int k = 0; k < count; k += 2) {
        const Pair fx = LoadPair(batch.fx + k), fy = LoadPair(batch.fy + k);
        Pair tix{}, tiy{}, tjx{}, tjy{}, sx{}, sy{};
        if constexpr (kUseFriction) {
          tix = LoadPair(batch.tix + k);
          tiy = LoadPair(batch.tiy + k);
          tjx = LoadPair(batch.tjx + k);
          tjy = LoadPair(batch.tjy + k);
          sx = LoadPair(batch.sx + k);
          sy = LoadPair(batch.sy + k);
        }
        scatter(k, Firsts(fx, fy), Firsts(tix, tiy), Firsts(tjx, tjy), Firsts(sx, sy));
        if (k + 1 < count) {
          scatter(k + 1, Seconds(fx, fy), Seconds(tix, tiy), Seconds(tjx, tjy), Seconds(sx, sy));
        }
      }
      flush();
      if (advance_inline) {
        const int64_t complete = q1 < near_end ? near_i[q1] : n;
        advance(advanced, complete, max2);
        advanced = complete;
      }
    }
    if (advance_inline) advance(advanced, n, max2);
    thread_sums_[t] = local;
#pragma omp barrier
    if (threads > 1) {
      // Each thread adds to its own particles the halos of the threads
      // before it, in the order of the sums before halos existed
      // ((((S_0 + S_1) + …) + S_t, addition being commutative), and zeroes
      // them for the next evaluation. It visits only the spheres that an
      // earlier thread's pairs reach (that thread's near list's `remote`):
      // no other halo entry is non-zero, and adding a zero changes no sum
      // here (none is −0: each starts from +0, and x + y is −0 only for
      // x = y = −0). The halos of threads 1 … t−1 go into thread 0's, in
      // thread order, and that into the thread's own sums; a sphere that
      // several lists name adds a zero the second time. At 10 000 spheres
      // on 2 threads the reached spheres are a third of the second
      // thread's, and their lines come from the other core (bench/README.md,
      // eighth round).
      auto reached = [&](int u) {
        const std::vector<int32_t>& remote = near_.pairs(u).remote;
        const auto first = std::lower_bound(remote.begin(), remote.end(), begin);
        return std::make_pair(first, std::lower_bound(first, remote.end(), end));
      };
      auto add_halos = [&](std::vector<std::vector<Vec4>>& halos, Vec4* own) {
        Vec4* total = halos[0].data();
        for (int u = 1; u < t; ++u) {
          Vec4* halo = halos[u].data();
          const auto [first, last] = reached(u);
          for (auto it = first; it != last; ++it) {
            const int32_t i = *it;
            total[i].x += halo[i].x;
            total[i].y += halo[i].y;
            total[i].z += halo[i].z;
            halo[i] = Vec4{};
          }
        }
        for (int u = 0; u < t; ++u) {
          const auto [first, last] = reached(u);
          for (auto it = first; it != last; ++it) {
            const int32_t i = *it;
            own[i].x = total[i].x + own[i].x;
            own[i].y = total[i].y + own[i].y;
            own[i].z = total[i].z + own[i].z;
            total[i] = Vec4{};
          }
        }
      };
      if (t > 0) {
        add_halos(thread_force_, force_.data());
        if constexpr (kUseFriction) add_halos(thread_torque_, torque_.data());
      }
      if constexpr (kAdvanceToo) advance(begin, end, max2);
    }
    thread_max2_[t] = max2;
  }
  if constexpr (kSumStress || kSumStiffness) {
    Sums total;
    for (const Sums& s : thread_sums_) {
      for (int k = 0; k < 6; ++k) {
        total.stress[k] += s.stress[k];
        total.stiffness[k] += s.stiffness[k];
      }
      total.contacts += s.contacts;
      total.force_sum += s.force_sum;
    }
    const double inverse_volume = 1.0 / volume();
    for (int k = 0; k < 6; ++k) {
      total.stress[k] *= inverse_volume;
      total.stiffness[k] *= inverse_volume;
    }
    sums_ = total;
  }
  if constexpr (kAdvanceToo) {
    double max2 = 0.0;
    for (double m : thread_max2_) max2 = std::max(max2, m);
    FinishAdvance(max2);
  }
}

template <class PairLaw, unsigned... kFlags>
void Engine::RunKernel(const PairLaw& law, bool friction, unsigned flags,
                       std::integer_sequence<unsigned, kFlags...>) {
  using Kernel = void (Engine::*)(const PairLaw&);
  static constexpr Kernel kWithFriction[] = {&Engine::ComputeForcesImpl<PairLaw, true, kFlags>...};
  if (friction) {
    (this->*kWithFriction[flags])(law);
    return;
  }
  // Without friction there is no shear history to freeze, and a law with
  // rolling resistance is only chosen with friction.
  if constexpr (PairLaw::kRollingHistory) {
    GRANASYM_CHECK(false) << "rolling resistance without friction";
  } else {
    static constexpr Kernel kWithoutFriction[] = {
        &Engine::ComputeForcesImpl<PairLaw, false, (kFlags & ~kFrozen)>...};
    GRANASYM_CHECK((flags & kFrozen) == 0);
    (this->*kWithoutFriction[flags])(law);
  }
}

void Engine::PrepareList() {
  if (!forces_current_ && neighbors_.built()) {
    TightenDisplacement(neighbors_, position_, cell_, options_.threads, &max_displacement_);
  }
  // The scaled positions are not wrapped back into the cell at a build (the
  // list bins them wrapped, and the minimum image is exact for any of them):
  // a wrap would change the rounding of later drifts at the build's step,
  // so the results would depend on when the list is rebuilt, i.e. on the
  // skin. Without it they do not: the skin and the rebuild times change
  // only which non-touching pairs are listed (the history of every touching
  // pair is carried, and the pairs are summed in the order (i, j)
  // whichever others are listed). Scaled positions move only by the
  // fluctuations (the affine motion is the cell's), so they stay within a
  // few cell sides of [0, 1).
  bool rebuilt = false;
  if (!forces_current_ && neighbors_.NeedsRebuild(max_displacement_, cell_)) {
    neighbors_.Build(position_, cell_, skin_, options_.threads);
    DeriveLoadedFlags();
    max_displacement_ = 0.0;
    rebuilt = true;
  }
  // The near list likewise, from the neighbour list (after a restore it is
  // built at the restored positions, also before a re-evaluation there).
  bool rebuild_near = rebuilt || !near_.built();
  const bool measured =
      !rebuild_near && !forces_current_ &&
      TightenDisplacement(near_, position_, cell_, options_.threads, &near_displacement_);
  if (measured) {
    ++near_measurements_;
    rebuild_near = near_.NeedsRebuild(near_displacement_, cell_);
  }
  if (!rebuild_near) return;
  if (near_.built() && step_ > near_build_step_) {
    // Its skin for the next build: from how fast this one's was used up.
    if (!measured) near_displacement_ = near_.MaxDisplacement(position_, cell_, options_.threads);
    const double used_per_step =
        near_.SkinUsed(near_displacement_, cell_) / static_cast<double>(step_ - near_build_step_);
    const double overhead = NearList::BuildOverhead(near_.listed_at_build(), size(),
                                                    near_measurements_ + (measured ? 0 : 1));
    near_skin_ = NearList::CheapestSkin(near_.skin(), overhead, near_.pair_count(),
                                        near_.touching_at_build(), used_per_step,
                                        kSmallestNearSkinRatio * skin_, skin_);
  }
  NearList::History history;
  if (friction_) {
    history.loaded = loaded_.data();
    history.shear = neighbors_.shear().data();
    if (!neighbors_.rolling().empty()) history.rolling = neighbors_.rolling().data();
  }
  near_.Build(neighbors_, position_, cell_, near_skin_, options_.threads, history);
  near_displacement_ = 0.0;
  near_build_step_ = step_;
  near_measurements_ = 0;
}

void Engine::Evaluate(Request request, bool advance) {
  PrepareList();
  // A second evaluation at unchanged positions must not slide the contacts
  // again: it reuses the shear forces (and rolling moments) of the first.
  const unsigned flags = (request.stress ? kStress : 0u) | (request.stiffness ? kStiffness : 0u) |
                         (forces_current_ && friction_ ? kFrozen : 0u) | (advance ? kAdvance : 0u);
  std::visit(
      [&](const auto& law) {
        RunKernel(law, friction_, flags, std::make_integer_sequence<unsigned, 16>{});
      },
      law_);
  forces_current_ = !advance;
}

void Engine::ComputeForces(Request request) { Evaluate(request, false); }

template <unsigned kFlags>
void Engine::IntegrateImpl() {
  constexpr bool kUseFriction = (kFlags & kRotation) != 0;
  constexpr bool kUseDamping = (kFlags & kDamping) != 0;
  const int64_t n = static_cast<int64_t>(position_.size());
  const double dt = options_.time_step;
  const double chi = material_.local_damping;
  const Lanes inverse_cell = {1.0 / cell_[0], 1.0 / cell_[1], 1.0 / cell_[2], 0.0};
  double max2 = 0.0;
#pragma omp parallel for num_threads(options_.threads) schedule(static) reduction(max : max2)
  for (int64_t i = 0; i < n; ++i) {
    max2 = std::max(max2, AdvanceParticle<kUseFriction, kUseDamping>(force_[i], torque_[i], dt, chi,
                                                                     inverse_cell, &velocity_[i],
                                                                     &spin_[i], &position_[i]));
  }
  FinishAdvance(max2);
}

void Engine::FinishAdvance(double max_speed2) {
  const double dt = options_.time_step;
  // Both lists' displacement bounds: Σ Δt max_i |v_i|.
  const double largest_step = dt * std::sqrt(max_speed2);
  max_displacement_ += largest_step;
  near_displacement_ += largest_step;
  forces_current_ = false;
  // dH/dt = D H integrated exactly over the step for the constant diagonal D
  // (the forward-Euler H += Δt D H would change the volume of an isochoric
  // path at second order, Δε_v ≈ −¾(ε̇_a Δt)² per step).
  for (int d = 0; d < 3; ++d) cell_[d] *= std::exp(dt * gradient_[d]);
  time_ += dt;
  ++step_;
}

void Engine::Integrate() {
  using Kernel = void (Engine::*)();
  static constexpr Kernel kKernels[4] = {&Engine::IntegrateImpl<0>, &Engine::IntegrateImpl<1>,
                                         &Engine::IntegrateImpl<2>, &Engine::IntegrateImpl<3>};
  const unsigned flags = (friction_ ? kRotation : 0u) | (damping_ ? kDamping : 0u);
  (this->*kKernels[flags])();
}

void Engine::SetTimeStep(double time_step) {
  GRANASYM_CHECK(time_step > 0 && std::isfinite(time_step)) << "time step " << time_step;
  options_.time_step = time_step;
  law_ = MakeLaw(material_, time_step);
}

double Engine::SmallestContactDuration() const {
  GRANASYM_CHECK(forces_current_)
      << "SmallestContactDuration needs the neighbour list of the current positions: call it "
         "after ComputeForces";
  // The shortest duration is that of the largest k_n (1/m_i + 1/m_j): one
  // pass over the listed pairs, a max reduction (exact, so independent of
  // the thread count).
  const int64_t n = static_cast<int64_t>(position_.size());
  const double lx = cell_[0], ly = cell_[1], lz = cell_[2];
  const int64_t* offsets = neighbors_.offsets().data();
  const int32_t* neighbor = neighbors_.neighbors().data();
  const Vec4* position = position_.data();
  const Vec4* velocity = velocity_.data();
  const int threads = options_.threads;
  const double largest = std::visit(
      [&](const auto& law) {
        double stiffest = 0.0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : stiffest)
        for (int64_t i = 0; i < n; ++i) {
          const Vec4 pi = position[i];
          for (int64_t p = offsets[i]; p < offsets[i + 1]; ++p) {
            const Vec4 pj = position[neighbor[p]];
            const Vec3 l = Branch(pi, pj, lx, ly, lz);
            const double distance2 = Dot(l, l);
            const double reach = pi.w + pj.w;
            if (!(distance2 < reach * reach)) continue;
            const double stiffness = law.NormalStiffness(pi.w, pj.w, std::sqrt(distance2));
            stiffest = std::max(stiffest, stiffness * (velocity[i].w + velocity[neighbor[p]].w));
          }
        }
        return stiffest;
      },
      law_);
  return largest > 0 ? kPi / std::sqrt(largest) : std::numeric_limits<double>::infinity();
}

void Engine::Step(Request request) { Evaluate(request, true); }

void Engine::Step() { Step(Request{}); }

Packing Engine::CurrentPacking() const {
  Packing packing;
  packing.cell = cell_;
  const size_t n = size();
  packing.positions.resize(n);
  packing.radii.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const int64_t i = id_[k];
    const Vec4& s = position_[k];
    packing.positions[i] = {cell_[0] * (s.x - std::floor(s.x)), cell_[1] * (s.y - std::floor(s.y)),
                            cell_[2] * (s.z - std::floor(s.z))};
    packing.radii[i] = s.w;
  }
  return packing;
}

Engine::State Engine::Save() const {
  State state;
  state.position = position_;
  state.velocity = velocity_;
  state.spin = spin_;
  state.id = id_;
  state.cell = cell_;
  state.gradient = gradient_;
  state.time = time_;
  state.step = step_;
  state.time_step = options_.time_step;
  state.max_displacement = max_displacement_;
  state.forces_current = forces_current_;
  state.neighbors = neighbors_.Save();
  return state;
}

void Engine::Restore(State state) {
  GRANASYM_CHECK(state.position.size() == position_.size())
      << "checkpoint has " << state.position.size() << " particles, the engine "
      << position_.size();
  position_ = std::move(state.position);
  velocity_ = std::move(state.velocity);
  spin_ = std::move(state.spin);
  id_ = std::move(state.id);
  cell_ = state.cell;
  gradient_ = state.gradient;
  time_ = state.time;
  step_ = state.step;
  if (state.time_step > 0) SetTimeStep(state.time_step);
  max_displacement_ = state.max_displacement;
  forces_current_ = state.forces_current;
  neighbors_.Restore(std::move(state.neighbors));
  DeriveLoadedFlags();
  near_.Clear();
}

void Engine::DeriveLoadedFlags() {
  // A pair may hold a history when its shear force or rolling moment is not
  // zero; the pair loop keeps the flag from then on (set while touching).
  const size_t pairs = neighbors_.pair_count();
  loaded_.assign(friction_ ? pairs : 0, 0);
  if (!friction_) return;
  const std::vector<Vec3>& shear = neighbors_.shear();
  const std::vector<Vec3>& rolling = neighbors_.rolling();
  auto nonzero = [](const Vec3& v) { return v.x != 0.0 || v.y != 0.0 || v.z != 0.0; };
  for (size_t p = 0; p < pairs; ++p) {
    loaded_[p] = nonzero(shear[p]) || (!rolling.empty() && nonzero(rolling[p]));
  }
}

}  // namespace granasym::dem
