#include "pipeline/raster_lanes.hpp"

namespace passim {

std::atomic<std::uint64_t> RasterLanes::threaded_runs{0};
std::atomic<std::uint64_t> RasterLanes::tasks_run{0};

RasterLanes::RasterLanes(Framebuffer& fb, int lanes) : jobs_(std::make_unique<Job[]>(kMaxJobs)) {
  for (int k = 0; k < lanes; ++k) lanes_.push_back(std::make_unique<Lane>(fb, fb.config.width));
  for (int k = 1; k < lanes; ++k) workers_.emplace_back([this, k] { worker(k); });
}

RasterTarget RasterLanes::lane_target(int index) const {
  RasterTarget t = setup_.target;
  t.band_cycle = 1 + kWorkerBands * (lanes() - 1);
  t.band_first = index == 0 ? 0 : 1 + kWorkerBands * (index - 1);
  t.band_count = index == 0 ? 1 : kWorkerBands;
  return t;
}

void RasterLanes::run_own_rows() {
  Lane& lane = *lanes_[0];
  if (own_done_ == 0) lane.stages.connect(setup_);
  run_jobs(lane, lane_target(0), own_done_, queued_);
  own_done_ = queued_;
}

RasterLanes::~RasterLanes() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  work_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void RasterLanes::add(const Job& job, const FragmentStagesSetup& setup, Counters& pass) {
  if (queued_ > 0 && (queued_ >= kMaxJobs || !(setup == setup_))) flush(pass);
  if (queued_ == 0) {
    setup_ = setup;
    // The texel caches are made once, here, before any lane samples (they are made lazily).
    if (setup_.texture) TextureStage::make_caches(setup_.texture_setup);
  }
  jobs_[queued_++] = job;
  if (queued_ % kChunk == 0) {
    publish();
    run_own_rows();
  }
}

void RasterLanes::triangle(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                           const TriangleOptions& options, const FragmentStagesSetup& setup, Counters& pass) {
  add(Job{{a, b, c}, options, false, 1.0}, setup, pass);
}

void RasterLanes::point(const RasterVertex& v, double size, const FragmentStagesSetup& setup, Counters& pass) {
  add(Job{{v, v, v}, TriangleOptions{}, true, size}, setup, pass);
}

void RasterLanes::publish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    published_ = queued_;
  }
  work_.notify_all();
}

void RasterLanes::run_jobs(Lane& lane, const RasterTarget& target, std::size_t from, std::size_t to) const {
  for (std::size_t k = from; k < to; ++k) {
    const Job& job = jobs_[k];
    if (job.is_point)
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
  work_.notify_all();
  std::exception_ptr error;
  try {
    task(0);
  } catch (...) {
    error = std::current_exception();
  }
  // Lanes that have not taken the task by now will not; wait for those that have.
  std::unique_lock<std::mutex> lock(mutex_);
  task_ = nullptr;
  finished_.wait(lock, [&] { return tasks_active_ == 0; });
  if (!error) error = task_error_;
  task_error_ = nullptr;
  if (error) std::rethrow_exception(error);
}

void RasterLanes::worker(int index) {
  Lane& lane = *lanes_[static_cast<std::size_t>(index)];
  std::uint64_t batch = 0, task_serial = 0;
  std::size_t done = 0;
  bool reported = false;
  RasterTarget target;
  for (;;) {
    std::size_t upto = 0;
    const std::function<void(int)>* task = nullptr;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      for (;;) {
        if (stop_) return;
        if (task_serial_ != task_serial) {
          task_serial = task_serial_;
          task = task_;  // null when the calling thread has finished it meanwhile
          if (task) {
            ++tasks_active_;
            break;
          }
        }
        if (batch_ != batch) {
          batch = batch_;
          done = 0;
          reported = false;
        }
        if (published_ > done || (closing_ && !reported)) break;
        work_.wait(lock);
      }
      upto = published_;
    }
    if (task) {
      std::exception_ptr error;
      try {
        (*task)(index);
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mutex_);
      if (error && !task_error_) task_error_ = error;
      if (--tasks_active_ == 0) finished_.notify_all();
      continue;
    }
    if (upto > done) {
      if (done == 0) {  // a new queue: its setup was written before its first job was published
        lane.stages.connect(setup_);
        target = lane_target(index);
      }
      try {
        run_jobs(lane, target, done, upto);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!error_) error_ = std::current_exception();
      }
      done = upto;
      continue;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    reported = true;
    if (++finished_lanes_ == static_cast<int>(workers_.size())) finished_.notify_all();
  }
}

void RasterLanes::flush(Counters& pass) {
  if (queued_ == 0) return;
  std::exception_ptr error;
  Lane& own = *lanes_[0];
  if (queued_ < kChunk) {
    // Never published: this thread, every row.
    own.stages.connect(setup_);
    try {
      run_jobs(own, setup_.target, 0, queued_);
    } catch (...) {
      error = std::current_exception();
    }
  } else {
    threaded_runs.fetch_add(1, std::memory_order_relaxed);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      published_ = queued_;
      closing_ = true;
    }
    work_.notify_all();
    try {
      run_own_rows();
    } catch (...) {
      error = std::current_exception();
    }
    std::unique_lock<std::mutex> lock(mutex_);
    finished_.wait(lock, [&] { return finished_lanes_ == static_cast<int>(workers_.size()); });
    if (!error) error = error_;
    error_ = nullptr;
    published_ = 0;
    closing_ = false;
    finished_lanes_ = 0;
    ++batch_;
  }
  for (const auto& lane : lanes_) {
    pass += lane->counters;
    lane->counters = Counters{};
  }
  queued_ = 0;
  own_done_ = 0;
  if (error) std::rethrow_exception(error);
}

}  // namespace passim
