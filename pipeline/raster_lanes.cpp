#include "pipeline/raster_lanes.hpp"

#include <algorithm>

namespace passim {

ChunkClaims::ChunkClaims(std::size_t count, int lanes)
    : count_(count), lanes_(std::max(lanes, 1)), shares_(std::make_unique<Share[]>(static_cast<std::size_t>(lanes_))) {
  const auto n = static_cast<std::size_t>(lanes_);
  for (std::size_t k = 0; k < n; ++k) {
    shares_[k].next.store(count * k / n, std::memory_order_relaxed);
    shares_[k].end = count * (k + 1) / n;
  }
}

std::size_t ChunkClaims::next(int lane) {
  for (int k = 0; k < lanes_; ++k) {
    Share& share = shares_[static_cast<std::size_t>((lane + k) % lanes_)];
    if (share.next.load(std::memory_order_relaxed) >= share.end) continue;
    const std::size_t chunk = share.next.fetch_add(1, std::memory_order_relaxed);
    if (chunk < share.end) return chunk;
  }
  return count_;
}

std::atomic<std::uint64_t> RasterLanes::threaded_runs{0};
std::atomic<std::uint64_t> RasterLanes::tasks_run{0};

RasterLanes::RasterLanes(Framebuffer& fb, int lanes)
    : jobs_(std::make_unique<Job[]>(kMaxJobs)), lane_batch_(static_cast<std::size_t>(lanes), 0),
      groups_(static_cast<std::size_t>(kGroupsPerLane * lanes)) {
  for (int stripe = 0; stripe * kStripeRows < fb.config.height; ++stripe)
    stripe_groups_.push_back(static_cast<std::uint16_t>(stripe % static_cast<int>(groups_.size())));
  for (int k = 0; k < lanes; ++k) lanes_.push_back(std::make_unique<Lane>(fb, fb.config.width));
  for (int k = 1; k < lanes; ++k) workers_.emplace_back([this, k] { worker(k); });
}

void RasterLanes::notify(std::condition_variable& cv) {
  announcements_.fetch_add(1, std::memory_order_release);
  cv.notify_all();
}

template <class Ready>
void RasterLanes::wait(std::unique_lock<std::mutex>& lock, std::condition_variable& cv, Ready ready) {
  if (ready()) return;
  const std::uint64_t seen = announcements_.load(std::memory_order_acquire);
  lock.unlock();
  const auto until = std::chrono::steady_clock::now() + kSpin;
  for (int k = 1;; ++k) {
    if (announcements_.load(std::memory_order_acquire) != seen) break;
    if (k % 64 == 0 && std::chrono::steady_clock::now() > until) break;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  lock.lock();
  cv.wait(lock, ready);
}

RasterTarget RasterLanes::group_target(int group) const {
  RasterTarget t = setup_.target;
  t.band_rows = kStripeRows;
  t.band_cycle = static_cast<int>(groups_.size());
  t.band_first = group;  // group 0 counts the per-primitive counters
  t.band_count = 1;
  return t;
}

int RasterLanes::claimable(int from, std::size_t backlog) const {
  const int n = static_cast<int>(groups_.size());
  for (int k = 0; k < n; ++k) {
    const int g = (from + k) % n;
    const Group& group = groups_[static_cast<std::size_t>(g)];
    if (!group.busy && group.done + backlog <= published_) return g;
  }
  return -1;
}

bool RasterLanes::all_run() const {
  for (const Group& group : groups_)
    if (group.busy || group.done < published_) return false;
  return true;
}

void RasterLanes::run_groups(int index, std::unique_lock<std::mutex>& lock, std::size_t backlog) {
  Lane& lane = *lanes_[static_cast<std::size_t>(index)];
  // Lanes start their search at different groups, so that they rarely meet on one.
  const int from = index * kGroupsPerLane;
  for (int g = claimable(from, backlog); g >= 0; g = claimable(from, backlog)) {
    Group& group = groups_[static_cast<std::size_t>(g)];
    group.busy = true;
    const std::size_t first = group.done, last = published_;
    const bool connect = lane_batch_[static_cast<std::size_t>(index)] != batch_;
    lane_batch_[static_cast<std::size_t>(index)] = batch_;
    lock.unlock();
    std::exception_ptr error;
    try {
      // A new queue: its setup was written before its first job was published.
      if (connect) lane.stages.connect(setup_);
      run_jobs(lane, group_target(g), first, last);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error && !error_) error_ = error;
    group.done = last;
    group.busy = false;
    if (group.done < published_) notify(work_);  // more came meanwhile: for a sleeping lane
    if (all_run()) notify(finished_);
  }
}

RasterLanes::~RasterLanes() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  notify(work_);
  for (std::thread& t : workers_) t.join();
}

void RasterLanes::add(const Job& job, std::size_t primitives, const FragmentStagesSetup& setup, Counters& pass) {
  if (queued_ > 0 && (queued_ >= kMaxJobs || !(setup == setup_))) flush(pass);
  if (queued_ == 0) {
    setup_ = setup;
    // The texel caches are made once, here, before any lane samples (they are made lazily).
    if (setup_.texture) TextureStage::make_caches(setup_.texture_setup, row_splitter_);
  }
  jobs_[queued_++] = job;
  const std::size_t before = primitives_;
  primitives_ += primitives;
  if (primitives_ / kChunk != before / kChunk) {
    std::unique_lock<std::mutex> lock(mutex_);
    published_ = queued_;
    notify(work_);
    run_groups(0, lock, kHelpBacklog);
  }
}

void RasterLanes::triangle(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                           const TriangleOptions& options, const FragmentStagesSetup& setup, Counters& pass) {
  add(Job{{a, b, c}, options, false, 1.0}, 1, setup, pass);
}

void RasterLanes::triangles(const AssembledTriangle* first, const TriangleRows* rows, std::size_t count,
                            const TriangleOptions& options, const FragmentStagesSetup& setup, Counters& pass) {
  if (count == 0) return;
  Job job;
  job.options = options;
  job.run = first;
  job.run_rows = rows;
  job.run_count = count;
  add(job, count, setup, pass);
}

void RasterLanes::point(const RasterVertex& v, double size, const FragmentStagesSetup& setup, Counters& pass) {
  add(Job{{v, v, v}, TriangleOptions{}, true, size}, 1, setup, pass);
}
void RasterLanes::line(const RasterVertex& a, const RasterVertex& b, const TriangleOptions& attributes,
                       const LineOptions& options, const FragmentStagesSetup& setup, Counters& pass) {
  Job job{{a, b, b}, attributes, false, 1.0};
  job.is_line = true;
  job.line_options = options;
  add(job, 1, setup, pass);
}

void RasterLanes::run_jobs(Lane& lane, const RasterTarget& target, std::size_t from, std::size_t to) const {
  for (std::size_t k = from; k < to; ++k) {
    const Job& job = jobs_[k];
    if (job.run) {
      TriangleOptions options = job.options;
      // The triangles with rows in this group's stripes, found without a branch per triangle
      // (which group holds a triangle is as good as random: a branch mispredicted half the
      // time cost more than the test). A triangle over three stripes or more is handed to
      // rasterize_triangle, which looks closer; the others are passed over here, counted as
      // rasterize_triangle counts them.
      constexpr std::size_t kBlock = 64;
      std::uint32_t drawn[kBlock];
      for (std::size_t first = 0; first < job.run_count; first += kBlock) {
        const std::size_t end = std::min(job.run_count, first + kBlock);
        std::size_t n = 0;
        for (std::size_t t = first; t < end; ++t) {
          const TriangleRows& rows = job.run_rows[t];
          // Rows lie in [0, height) (empty: first 0, last −1, which the division takes to 0).
          const std::int32_t a = rows.first / kStripeRows, b = rows.last / kStripeRows;
          const std::size_t in_a = stripe_groups_[static_cast<std::size_t>(a)] == target.band_first;
          const std::size_t in_b = stripe_groups_[static_cast<std::size_t>(b)] == target.band_first;
          const std::size_t tall = b - a >= 2;
          drawn[n] = static_cast<std::uint32_t>(t);
          n += in_a | in_b | tall;
        }
        if (target.counts_primitives()) lane.counters.triangles_rasterized += (end - first) - n;
        for (std::size_t k = 0; k < n; ++k) {
          // The next triangle's cache lines are asked for now: it was assembled on another
          // lane, or long enough ago to have left this one's cache.
          if (k + 1 < n) {
            const char* next = reinterpret_cast<const char*>(&job.run[drawn[k + 1]]);
            for (std::size_t line = 0; line < sizeof(AssembledTriangle); line += 64) __builtin_prefetch(next + line);
            __builtin_prefetch(next + sizeof(AssembledTriangle) - 1);  // the last line, when it straddles one more
          }
          const AssembledTriangle& triangle = job.run[drawn[k]];
          options.flat_color = triangle.flat_color;
          rasterize_triangle(triangle.v[0], triangle.v[1], triangle.v[2], options, target, lane.spans,
                             *lane.stages.first, lane.counters, &job.run_rows[drawn[k]]);
        }
      }
    } else if (job.is_line)
      rasterize_line(job.v[0], job.v[1], job.options, job.line_options, target, lane.spans, *lane.stages.first,
                     lane.counters);
    else if (job.is_point)
      rasterize_point(job.v[0], job.point_size, target, lane.spans, *lane.stages.first, lane.counters);
    else
      rasterize_triangle(job.v[0], job.v[1], job.v[2], job.options, target, lane.spans, *lane.stages.first,
                         lane.counters);
  }
}

void RasterLanes::run_task(const std::function<void(int)>& task) {
  tasks_run.fetch_add(1, std::memory_order_relaxed);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    task_ = &task;
    ++task_serial_;
  }
  notify(work_);
  std::exception_ptr error;
  try {
    task(0);
  } catch (...) {
    error = std::current_exception();
  }
  // Lanes that have not taken the task by now will not; wait for those that have.
  std::unique_lock<std::mutex> lock(mutex_);
  task_ = nullptr;
  wait(lock, finished_, [&] { return tasks_active_ == 0; });
  if (!error) error = task_error_;
  task_error_ = nullptr;
  if (error) std::rethrow_exception(error);
}

void RasterLanes::worker(int index) {
  std::uint64_t task_serial = 0;
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wait(lock, work_, [&] { return stop_ || task_serial_ != task_serial || claimable(index * kGroupsPerLane) >= 0; });
    if (stop_) return;
    if (task_serial_ != task_serial) {
      task_serial = task_serial_;
      const std::function<void(int)>* task = task_;  // null when the calling thread has finished it meanwhile
      if (!task) continue;
      ++tasks_active_;
      lock.unlock();
      std::exception_ptr error;
      try {
        (*task)(index);
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      if (error && !task_error_) task_error_ = error;
      if (--tasks_active_ == 0) notify(finished_);
      continue;
    }
    run_groups(index, lock);
  }
}

void RasterLanes::flush(Counters& pass) {
  if (queued_ == 0) return;
  std::exception_ptr error;
  Lane& own = *lanes_[0];
  if (primitives_ < kChunk) {
    // Never published: this thread, every row.
    own.stages.connect(setup_);
    lane_batch_[0] = 0;  // connected for no queue of the lanes
    try {
      run_jobs(own, setup_.target, 0, queued_);
    } catch (...) {
      error = std::current_exception();
    }
  } else {
    threaded_runs.fetch_add(1, std::memory_order_relaxed);
    std::unique_lock<std::mutex> lock(mutex_);
    published_ = queued_;
    notify(work_);
    run_groups(0, lock);
    wait(lock, finished_, [&] { return all_run(); });
    error = error_;
    error_ = nullptr;
    published_ = 0;
    for (Group& group : groups_) group.done = 0;
    ++batch_;
  }
  for (const auto& lane : lanes_) {
    pass += lane->counters;
    lane->counters = Counters{};
  }
  queued_ = 0;
  primitives_ = 0;
  if (error) std::rethrow_exception(error);
}

}  // namespace passim
