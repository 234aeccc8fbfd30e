// DistributedWorld: one scene over the ranks of an MPI communicator, each rank
// a World over its subdomain (HCSITS's scheme, Preclik and Rüde 2015,
// "Ultrascale simulations of non-smooth granular dynamics", Comput. Part. Mech. 2).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <mpi.h>

#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/bodies/validation.hpp"
#include "gpusolve/rbd/distributed/mpi_body_exchange.hpp"
#if GPUSOLVE_WITH_NCCL
#include "gpusolve/rbd/distributed/nccl_body_exchange.hpp"
#endif
#include "gpusolve/rbd/distributed/owned_bodies_check.hpp"
#include "gpusolve/rbd/distributed/rank_agreement.hpp"
#include "gpusolve/rbd/distributed/rank_alarm.hpp"
#include "gpusolve/rbd/distributed/rank_communicator.hpp"
#include "gpusolve/rbd/distributed/rank_device.hpp"
#include "gpusolve/rbd/distributed/rank_grid.hpp"
#include "gpusolve/rbd/distributed/rank_messages.hpp"
#include "gpusolve/rbd/solvers/friction_anchors.hpp"
#include "gpusolve/rbd/world.hpp"

namespace gpusolve::rbd {

// How the ranks' solves exchange their sums: through host memory with MPI
// (either backend; ranks may share a GPU), or from GPU to GPU with NCCL (the
// GPU backend, a GPU per rank, a program built with GPUSOLVE_WITH_NCCL).
enum class RankTransport { mpi_host, nccl };

// The figures of one distributed step, the same on every rank.
template <class T>
struct DistributedStats {
  StepStats<T> local;           // this rank's World (its contacts; its bodies, shadows included)
  std::size_t contacts = 0;     // over the ranks: each contact is solved by one rank
  std::size_t bodies = 0;       // moving bodies, each counted by its owner
  T max_penetration = 0;        // over the ranks' contacts (StepStats::max_penetration)
  T kinetic_energy = 0;         // of the moving bodies, each counted once
  std::array<T, 3> momentum{};  // sum of m v over the moving bodies
  std::size_t shadows = 0;      // shadow copies held, over the ranks
  double seconds_bodies = 0;    // this rank: its bodies checked where they live and, before a step
                                // that moves bodies between ranks, read back, sent with the
                                // remembered contacts and the shadows, and the World rebuilt
  double seconds_exchange = 0;  // this rank: the solve's exchanges (sums and reductions), waits included
  double seconds_step = 0;      // this rank: the World's step, the solve's exchanges included (its
                                // phases in local.time_*, with set_phase_timing)
  bool rebuilt = false;         // the ranks' Worlds were rebuilt before the step (bodies changed ranks):
                                // only then were their bodies read back from where they live
};

// Each rank owns the moving bodies whose centre lies in its cell of a
// RankGrid over the scene, and holds shadow copies (BodyStatus::shadow) of
// the bodies that higher ranks own within contact reach and twice the skin
// (set_skin) of its cell; every
// fixed body is on every rank. A contact is solved by the lowest rank among
// its bodies' owners (a shadow meets only active bodies: collision_detection.hpp),
// and in every solver iteration the shadows' velocity changes are summed to
// their owners and the totals sent back (MpiBodyExchange); the residual
// checks and the momentum's sums are reduced over the ranks. Once a body has
// gone more than the skin past its cell, or towards a rank that holds no
// shadow of it, the bodies move to the ranks whose cells hold their centres
// and the shadows are sent again; whether any must is found where the bodies live
// (OwnedBodiesCheck), so a step that moves none reads no body back. A rank's
// bodies are kept in the order of their global ids, so every pair of bodies
// meets in the roles it has in one World over the whole scene, and the warm
// start follows the renumbering.
// Global ids: the bodies each rank passes in, numbered rank by rank.
//
// On either backend: each rank's World runs where its bodies live (ranks may
// share a GPU); the bodies that change ranks and the solve's sums travel
// through host memory (MpiBodyExchange), or with RankTransport::nccl the sums
// from GPU to GPU (NcclBodyExchange). Methods that run distributed: World's
// solves_distributed (every method of the library's). Every rank passes the same settings, and
// a BodySet with the same materials and compound types (a compound's parts are
// found by index on whichever rank holds it); the counts are checked. A rank that throws (a body
// that is not valid or not finite, named by its global id) makes every rank
// throw the same error (RankAgreement); one that fails inside a step ends the
// others' waits (RankAlarm), and they throw it too.
template <class Device = device::cpu, class T = float, class Model = ConeFriction,
          class Method = AcceleratedJacobi<Gather>, ShapeMask Shapes = all_shapes>
class DistributedWorld {
 public:
  using LocalWorld = World<Device, T, Model, Method, Shapes>;
  using Vec = std::array<T, 3>;

  // `mine`: the bodies this rank adds (all on one rank and none on the
  // others, or any split). The grid spans the moving bodies' centres unless
  // lo and hi are given. A transport this program cannot use
  // (RankTransport::nccl on the CPU backend or without GPUSOLVE_WITH_NCCL)
  // is refused on every rank with UnsupportedError.
  DistributedWorld(MPI_Comm comm, const BodySet<T>& mine, const SolverSettings<T>& settings,
                   std::optional<std::pair<Vec, Vec>> box = std::nullopt,
                   RankTransport transport = RankTransport::mpi_host)
      : comm_(comm),
        alarm_(comm),
        agree_(comm_, &alarm_),
        messages_(comm, &alarm_),
        local_(mine),
        exchange_(make_exchange(comm, transport, &alarm_)) {
    rank_ = comm_.rank(), ranks_ = comm_.ranks();
    local_.records().clear();
    require_same_everywhere(mine);
    std::vector<Placed> added = number(mine);
    agree_.run([&] { validate(added); });
    const std::vector<Placed> fixed_everywhere = gather_fixed(added);
    largest_ = largest_bound(added);
    reach_ = largest_ + settings.margin;
    skin_ = default_skin_share * largest_;
    box_ = box ? *box : span(added);
    grid_.emplace(grid_for(skin_));
    std::vector<Placed> owned;
    for (const Placed& p : added)
      if (p.body.status != fixed) owned.push_back(p);
    std::vector<Placed>().swap(added);  // one copy of the bodies at a time
    fixed_ = fixed_everywhere;
    owned = send_to_owners(owned);
    alarm_.guard([&] {
      world_.emplace(local_, settings);
      // One rank shares nothing: its World solves as any World does (on the GPU,
      // one persistent kernel); the method must still be one that runs distributed.
      world_->set_exchange(exchange_.get());
      if (ranks_ == 1) world_->set_exchange(nullptr);
      rebuild(owned, {});
    });
  }

  // One step of the whole scene; every rank calls it. The ranks' Worlds are
  // rebuilt only where a body goes past its cell or towards a rank without
  // its shadow by more than the skin (set_skin), holds a state that is not
  // finite (the rebuild's check names it on every rank), or was modified:
  // otherwise every shadow has moved exactly as its owner (the same velocity
  // sums, the same integration). A rank that fails
  // inside a step (out of memory, a failed launch) raises the alarm
  // (RankAlarm): the other ranks' waits end and they throw the same error,
  // named by that rank. A world that threw must not be stepped again (its
  // ranks' states and messages are left where the failure found them).
  DistributedStats<T> step() {
    return alarm_.guard([&] { return take_step(); });
  }

  // The moving bodies this rank owns after the last step, with their global ids.
  std::vector<std::pair<std::uint64_t, Body<T>>> owned() {
    std::vector<std::pair<std::uint64_t, Body<T>>> out;
    for (const Placed& p : own_bodies()) out.push_back({p.gid, p.body});
    return out;
  }

  // How far (m) a body may go past its rank's cell, or towards a rank that
  // holds no shadow of it, before the ranks' Worlds are rebuilt; shadows are
  // sent that much farther on each side. A wider skin rebuilds less often and
  // holds more shadows (docs/distributed.md); the default is
  // default_skin_share of the largest moving body's bound. Every rank calls
  // it with the same value (else, or for one not finite or negative, every
  // rank throws InvalidArgumentError; for one whose reach spans more than 64
  // of the ranks' cells, UnsupportedError, as RankGrid; nothing changes then);
  // the next step rebuilds.
  static constexpr T default_skin_share = T(0.25);
  void set_skin(T skin) {
    int bad = !(skin >= T(0) && skin <= std::numeric_limits<T>::max());
    alarm_.allreduce(&bad, 1, MPI_INT, MPI_LOR, comm_);
    if (bad) throw InvalidArgumentError("gpusolve: DistributedWorld::set_skin: the skin must be finite and >= 0 on every rank");
    T lo = skin, hi = skin;
    alarm_.allreduce(&lo, 1, detail::mpi_type<T>(), MPI_MIN, comm_);
    alarm_.allreduce(&hi, 1, detail::mpi_type<T>(), MPI_MAX, comm_);
    if (lo != hi) throw InvalidArgumentError("gpusolve: DistributedWorld::set_skin: the ranks passed different skins");
    RankGrid<T> grid = grid_for(skin);  // a reach past 64 cells throws here, every rank alike, before anything changes
    skin_ = skin;
    grid_.emplace(grid);
    modified_ = true;
  }
  T skin() const { return skin_; }

  // Per-phase timing of each rank's World (World::set_phase_timing): the
  // steps' local.time_* figures.
  void set_phase_timing(bool on) { world_->set_phase_timing(on); }

  // Calls f(body) for the moving body with global id `gid` on the rank that
  // owns it (returns whether this rank does); the next step takes it as
  // changed. Every rank calls it.
  template <class F>
  bool modify(std::uint64_t gid, F&& f) {
    collect_owned();
    const auto at = std::lower_bound(gids_.begin(), gids_.end(), gid);
    if (at == gids_.end() || *at != gid) return false;
    Body<T>& b = local_[std::size_t(at - gids_.begin())];
    if (b.status != active) return false;  // a shadow or fixed body: not this rank's
    f(b);
    modified_ = true;
    return true;
  }

  // Every body of the scene in the order of the global ids, on rank `root`
  // (empty elsewhere): moving bodies from their owners, fixed ones as added.
  std::vector<Body<T>> gather(int root = 0) {
    std::vector<Placed> all = messages_.gather_to(own_bodies(), root);
    if (rank_ != root) return {};
    all.insert(all.end(), fixed_.begin(), fixed_.end());
    std::sort(all.begin(), all.end(), [](const Placed& a, const Placed& b) { return a.gid < b.gid; });
    std::vector<Body<T>> out;
    for (const Placed& p : all) out.push_back(p.body);
    return out;
  }

 private:
  // step()'s work: the bodies that change ranks moved, the Worlds' step, the figures.
  DistributedStats<T> take_step() {
    const auto start = std::chrono::steady_clock::now();
    DistributedStats<T> out;
    out.rebuilt = bodies_change();
    if (out.rebuilt) {
      std::vector<Placed> owned = own_bodies();
      std::vector<std::vector<Remembered>> to = remembered_by_rank();
      owned = send_to_owners(owned);
      rebuild(owned, messages_.exchange(to));
    }
    ++steps_;
    const auto exchanged = std::chrono::steady_clock::now();
    exchange_->take_seconds();
    const StepStats<T> st = world_->step();
    stepped_ = true;
    out.seconds_step = std::chrono::duration<double>(std::chrono::steady_clock::now() - exchanged).count();
    out.seconds_exchange = exchange_->take_seconds();
    const auto back = std::chrono::steady_clock::now();
    own_ = check_.run(world_->bodies().view(), *grid_, rank_, reach_, skin_);
    out.seconds_bodies = std::chrono::duration<double>(exchanged - start).count() +
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - back).count();
    out.local = st;
    figures(st, out);
    return out;
  }

  // A body and its global id, as ranks send them (plain bytes).
  struct Placed {
    std::uint64_t gid;
    Body<T> body;
  };
  static_assert(std::is_trivially_copyable_v<Placed>);

  // A contact remembered for the warm start, by its bodies' global ids, as
  // ranks send it to the rank that solves it next (WarmStart's values: the
  // impulse, then a friction anchor or NaN where it keeps none).
  static constexpr std::size_t remembered_width = Model::rows + detail::anchor_values;
  struct Remembered {
    std::uint64_t a, b;
    std::uint32_t feature;
    T values[remembered_width];
  };

  // The exchange over `transport` (the same on every rank: it is a collective).
  static std::unique_ptr<RankExchange<T>> make_exchange(MPI_Comm comm, RankTransport transport, RankAlarm* alarm) {
    if (transport == RankTransport::mpi_host) return std::make_unique<MpiBodyExchange<Device, T>>(comm, alarm);
#if GPUSOLVE_WITH_NCCL
    if constexpr (std::is_same_v<Device, device::gpu>) return std::make_unique<NcclBodyExchange<T>>(comm, alarm);
#endif
    throw UnsupportedError(std::is_same_v<Device, device::gpu>
                               ? "gpusolve: DistributedWorld: RankTransport::nccl needs a program built with NCCL "
                                 "(GPUSOLVE_WITH_NCCL)"
                               : "gpusolve: DistributedWorld: RankTransport::nccl needs the GPU backend");
  }

  // Global ids: this rank's bodies after those of the ranks before it.
  std::vector<Placed> number(const BodySet<T>& mine) const {
    std::uint64_t count = mine.size(), first = 0;
    MPI_Exscan(&count, &first, 1, MPI_UINT64_T, MPI_SUM, comm_);
    if (rank_ == 0) first = 0;
    std::vector<Placed> out;
    for (std::size_t k = 0; k < mine.size(); ++k) out.push_back({first + k, mine[k]});
    return out;
  }

  // A state that is not finite stops the step before it is taken, named as World names it.
  void require_finite_state(const Body<T>& b, std::uint64_t gid) const {
    const std::pair<const char*, const T*> state[] = {{"pos", b.pos.data()}, {"q", b.q.data()}, {"v", b.v.data()}, {"w", b.w.data()}};
    for (const auto& [field, x] : state)
      for (int c = 0; c < (field[0] == 'q' ? 4 : 3); ++c)
        if (!std::isfinite(x[c])) throw NonFiniteStateError(std::size_t(gid), field, steps_);
  }

  void validate(const std::vector<Placed>& bodies) const {
    for (const Placed& p : bodies) {
      if (p.body.status == shadow) throw InvalidBodyError(std::size_t(p.gid), "status", "shadows are the world's own");
      validate_body(p.body, std::size_t(p.gid), local_.parts());
    }
  }

  // Every rank's BodySet holds as many materials and compound parts as the
  // others' (the same lists, as the class says), or every rank throws.
  void require_same_everywhere(const BodySet<T>& mine) const {
    const std::uint64_t mine_counts[2] = {mine.materials().size(), mine.parts().size()};
    std::uint64_t low[2], high[2];
    MPI_Allreduce(mine_counts, low, 2, MPI_UINT64_T, MPI_MIN, comm_);
    MPI_Allreduce(mine_counts, high, 2, MPI_UINT64_T, MPI_MAX, comm_);
    if (low[0] != high[0] || low[1] != high[1])
      throw InvalidArgumentError("gpusolve: DistributedWorld: every rank must pass a BodySet with the same materials and "
                                 "compound types (materials " + std::to_string(low[0]) + " to " +
                                 std::to_string(high[0]) + ", compound parts " + std::to_string(low[1]) + " to " +
                                 std::to_string(high[1]) + " over the ranks)");
  }

  // Every rank's fixed bodies, on every rank.
  std::vector<Placed> gather_fixed(const std::vector<Placed>& added) const {
    std::vector<Placed> mine;
    for (const Placed& p : added)
      if (p.body.status == fixed) mine.push_back(p);
    return messages_.all_gather(mine);
  }

  // The grid of ranks over box_, for queries as far as a body's shadows reach with `skin`.
  RankGrid<T> grid_for(T skin) const { return RankGrid<T>(dims(), box_.first, box_.second, largest_ + reach_ + 2 * skin); }

  // The ranks along x and y (a pile is tall in z): MPI_Dims_create with z at 1.
  std::array<int, 3> dims() const {
    int d[3] = {0, 0, 1};
    MPI_Dims_create(ranks_, 3, d);
    return {d[0], d[1], d[2]};
  }

  // The box of the moving bodies' centres over the ranks.
  std::pair<Vec, Vec> span(const std::vector<Placed>& added) const {
    T lo[3], hi[3];
    for (int a = 0; a < 3; ++a) lo[a] = std::numeric_limits<T>::max(), hi[a] = -std::numeric_limits<T>::max();
    for (const Placed& p : added)
      if (p.body.status != fixed)
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p.body.pos[a]), hi[a] = std::max(hi[a], p.body.pos[a]);
    MPI_Allreduce(MPI_IN_PLACE, lo, 3, detail::mpi_type<T>(), MPI_MIN, comm_);
    MPI_Allreduce(MPI_IN_PLACE, hi, 3, detail::mpi_type<T>(), MPI_MAX, comm_);
    Vec l{}, h{};
    for (int a = 0; a < 3; ++a) l[a] = lo[a] <= hi[a] ? lo[a] : T(0), h[a] = lo[a] <= hi[a] ? hi[a] : T(0);
    return {l, h};
  }

  static T bound(const Body<T>& b) {
    return shape_bound<T>(b.shape, b.shape_param[0], b.shape_param[1], b.shape_param[2]);
  }

  // The largest bounding radius of a moving body, over the ranks.
  T largest_bound(const std::vector<Placed>& added) const {
    T r = 0;
    for (const Placed& p : added)
      if (p.body.status != fixed) r = std::max(r, bound(p.body));
    MPI_Allreduce(MPI_IN_PLACE, &r, 1, detail::mpi_type<T>(), MPI_MAX, comm_);
    return r;
  }

  // Sends each body to the rank whose cell holds its centre; returns the
  // bodies this rank owns, in the order of their ids.
  std::vector<Placed> send_to_owners(const std::vector<Placed>& bodies) {
    std::vector<std::vector<Placed>> to(ranks_);
    for (const Placed& p : bodies) to[grid_->owner(p.body.pos)].push_back(p);
    std::vector<Placed> mine = messages_.exchange(to);
    std::sort(mine.begin(), mine.end(), [](const Placed& a, const Placed& b) { return a.gid < b.gid; });
    return mine;
  }

  // The World's bodies in local_ as its last step left them, read back.
  void collect_owned() {
    if (!stepped_) return;
    world_->syncHost();
    stepped_ = false;
  }

  // The moving bodies this rank owns, with their global ids, as they are now.
  std::vector<Placed> own_bodies() {
    collect_owned();
    std::vector<Placed> out;
    for (std::size_t k = 0; k < local_.size(); ++k)
      if (local_[k].status == active) out.push_back({gids_[k], local_[k]});
    return out;
  }

  // The contacts this rank remembered in the last step, by the rank that
  // solves them next: the lower owner of their bodies once the bodies have
  // moved to the cells of their centres (a fixed body has no owner). Shadows
  // moved exactly as their owners did, so every rank finds the same owners.
  std::vector<std::vector<Remembered>> remembered_by_rank() {
    std::vector<std::vector<Remembered>> to(ranks_);
    const RememberedContacts<T> kept = world_->remembered_contacts();
    auto next_owner = [&](std::uint32_t k) {
      return local_[k].status == fixed ? ranks_ : grid_->owner(local_[k].pos);
    };
    for (std::size_t i = 0; i < kept.keys.size(); ++i) {
      const std::uint32_t a = pair_a(kept.keys[i]), b = pair_b(kept.keys[i]);
      Remembered m{gids_[a], gids_[b], kept.features[i], {}};
      for (std::size_t r = 0; r < remembered_width; ++r)
        m.values[r] = r < kept.width ? kept.values[i * kept.width + r] : std::numeric_limits<T>::quiet_NaN();
      to[std::min(next_owner(a), next_owner(b))].push_back(m);
    }
    return to;
  }

  // `moved` as the World's remembered contacts, by the new local indices
  // (with anchor values: a step whose contacts keep no anchors ignores them).
  void remember(const std::vector<Remembered>& moved) {
    RememberedContacts<T> kept;
    kept.width = remembered_width;
    auto local = [&](std::uint64_t gid) {
      return std::uint32_t(std::lower_bound(gids_.begin(), gids_.end(), gid) - gids_.begin());
    };
    std::vector<std::pair<std::uint64_t, std::size_t>> order;
    for (std::size_t i = 0; i < moved.size(); ++i) order.push_back({pair_key(local(moved[i].a), local(moved[i].b)), i});
    std::stable_sort(order.begin(), order.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& [key, i] : order) {
      kept.keys.push_back(key);
      kept.features.push_back(moved[i].feature);
      kept.values.insert(kept.values.end(), moved[i].values, moved[i].values + kept.width);
    }
    world_->remember(kept);
  }

  // The World's bodies again: the fixed ones, this rank's own (`owned`, by
  // id), and shadows of the bodies that higher ranks own within reach of this
  // rank's cell, in the order of their ids; the contacts it solves next
  // remembered (`moved`), the exchange told which bodies are shared.
  void rebuild(const std::vector<Placed>& owned, const std::vector<Remembered>& moved) {
    std::vector<std::vector<Placed>> to(ranks_);
    std::vector<std::vector<std::size_t>> sent(ranks_);  // indices into owned
    std::vector<std::uint64_t> shadowed_at(owned.size());  // per owned body: the ranks that hold its shadow
    for (std::size_t k = 0; k < owned.size(); ++k) {
      shadowed_at[k] = shadow_ranks(owned[k].body);
      for (int bit = 0; bit < 64; ++bit)
        if (shadowed_at[k] >> bit & 1u) {
          const int r = grid_->neighbour(rank_, bit);
          to[r].push_back(owned[k]);
          sent[r].push_back(k);
        }
    }
    // The shadows arrive rank by rank, each rank's in the order it sent them.
    std::vector<int> from;
    const std::vector<Placed> came = messages_.exchange(to, &from);
    // Merge fixed, owned and shadows by id.
    struct Entry {
      std::uint64_t gid;
      const Placed* p;
      int kind;  // 0 fixed, 1 owned (index `at` into owned), 2 shadow from rank `at`
      std::size_t at;
    };
    std::vector<Entry> all;
    for (const Placed& p : fixed_) all.push_back({p.gid, &p, 0, 0});
    for (std::size_t k = 0; k < owned.size(); ++k) all.push_back({owned[k].gid, &owned[k], 1, k});
    for (std::size_t k = 0; k < came.size(); ++k) all.push_back({came[k].gid, &came[k], 2, std::size_t(from[k])});
    std::sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) { return a.gid < b.gid; });
    std::vector<std::uint64_t> gids(all.size());
    std::vector<Body<T>>& records = local_.records();
    records.resize(all.size());
    SharedBodies shared;
    shared.shadows.assign(ranks_, {});
    shared.copies.assign(ranks_, {});
    std::vector<std::size_t> local_of_owned(owned.size());
    for (std::size_t k = 0; k < all.size(); ++k) {
      gids[k] = all[k].gid;
      records[k] = all[k].p->body;
      if (all[k].kind == 1) local_of_owned[all[k].at] = k;
      if (all[k].kind == 2) records[k].status = shadow;
    }
    // The order each rank sent its bodies in: their place among `came`.
    {
      std::vector<std::size_t> place(came.size());
      for (std::size_t k = 0; k < all.size(); ++k)
        if (all[k].kind == 2) place[std::size_t(all[k].p - came.data())] = k;
      for (std::size_t k = 0; k < came.size(); ++k) shared.shadows[from[k]].push_back(place[k]);
    }
    for (int r = 0; r < ranks_; ++r)
      for (std::size_t k : sent[r]) shared.copies[r].push_back(local_of_owned[k]);
    std::vector<std::uint64_t> shadowed_by_local(all.size(), 0);
    for (std::size_t k = 0; k < owned.size(); ++k) shadowed_by_local[local_of_owned[k]] = shadowed_at[k];
    // Every rank's bodies valid and finite before the World sees them, or the
    // same error on every rank, and no step.
    agree_.run([&] {
      for (std::size_t k = 0; k < records.size(); ++k) {
        require_finite_state(records[k], gids[k]);
        validate_body(records[k], std::size_t(gids[k]), local_.parts());
      }
    });
    gids_ = std::move(gids);
    shadows_ = came.size();
    world_->manager().syncDeviceFull();
    remember(moved);
    exchange_->share(shared);
    check_.shadowed_at(shadowed_by_local);
    own_ = OwnedBodies{};  // every body where it belongs, and finite
    modified_ = false;
  }

  // The lower ranks whose cells come within contact reach of body b and twice
  // the skin, which hold its shadow, as bits over this rank's neighbourhood
  // (RankGrid): enough while b and its partners each stay within the skin.
  std::uint64_t shadow_ranks(const Body<T>& b) const {
    return grid_->ranks_within(b.pos, bound(b) + reach_ + 2 * skin_, rank_);
  }

  // Whether any rank's bodies change before this step (a collective): a body
  // more than the skin past its cell, one that needs a shadow where there is
  // none, one whose state is not finite (OwnedBodiesCheck after the last
  // step), or one that was modified.
  bool bodies_change() {
    int change = modified_ || own_.to_move != 0 ? 1 : 0;
    alarm_.allreduce(&change, 1, MPI_INT, MPI_LOR, comm_);
    return change != 0;
  }

  // The step's figures over the ranks: owned bodies only, each contact once.
  void figures(const StepStats<T>& st, DistributedStats<T>& out) {
    double sums[6] = {own_.count, own_.kinetic_energy, own_.momentum[0], own_.momentum[1], own_.momentum[2],
                      double(shadows_)};  // bodies, energy, momentum, shadows
    alarm_.allreduce(sums, 6, MPI_DOUBLE, MPI_SUM, comm_);
    std::uint64_t contacts = st.solver.contacts;
    alarm_.allreduce(&contacts, 1, MPI_UINT64_T, MPI_SUM, comm_);
    T penetration = st.max_penetration;
    alarm_.allreduce(&penetration, 1, detail::mpi_type<T>(), MPI_MAX, comm_);
    out.bodies = std::size_t(sums[0]);
    out.kinetic_energy = T(sums[1]);
    for (int a = 0; a < 3; ++a) out.momentum[a] = T(sums[2 + a]);
    out.shadows = std::size_t(sums[5]);
    out.contacts = std::size_t(contacts);
    out.max_penetration = penetration;
  }

  RankCommunicator comm_;  // the world's own collectives
  int rank_ = 0, ranks_ = 1;
  RankAlarm alarm_;  // a failure inside a step ends every rank's waits
  RankAgreement agree_;
  RankMessages messages_;
  BodySet<T> local_;                   // the World's bodies: fixed, owned and shadows, by id
  std::vector<std::uint64_t> gids_;    // of local_'s bodies
  std::vector<Placed> fixed_;          // every rank's fixed bodies
  std::optional<RankGrid<T>> grid_;
  std::pair<Vec, Vec> box_;  // the grid's
  T largest_ = 0;  // the largest moving body's bound
  T reach_ = 0;    // a body's bound plus this is the farthest it makes contacts
  T skin_ = 0;     // set_skin
  std::unique_ptr<RankExchange<T>> exchange_;
  std::optional<LocalWorld> world_;
  OwnedBodiesCheck<Device, T> check_;
  OwnedBodies own_;  // the check of this rank's bodies after the last step or rebuild
  std::size_t shadows_ = 0;
  std::size_t steps_ = 0;  // steps taken
  bool stepped_ = false;  // the World holds state that local_ has not taken back
  bool modified_ = false;  // modify() changed a body since the last rebuild
};

}  // namespace gpusolve::rbd
