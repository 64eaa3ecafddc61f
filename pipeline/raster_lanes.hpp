// Rasterization and the fragment stages on several threads, bit-identical to one thread
// (docs/threads.md). The calling thread transforms, lights and clips, and queues each
// primitive with the stage setup it was drawn under; the lanes rasterize the queue as it
// grows, in order, each over its own rows only. Rows are dealt out in bands of
// RasterTarget::band_rows: in each cycle the calling thread (lane 0, which also does the
// vertex work) takes one band and every worker lane kWorkerBands. A pixel is therefore
// written by one lane, by the same primitives in the same order with the same arithmetic as
// on one thread; the counters are sums of integers, which do not depend on the order of adding.
#pragma once
#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "stages/fragment_stages.hpp"

namespace passim {

class RasterLanes {
 public:
  // `lanes` >= 2: the calling thread and lanes − 1 workers.
  RasterLanes(Framebuffer& fb, int lanes);
  ~RasterLanes();
  RasterLanes(const RasterLanes&) = delete;
  RasterLanes& operator=(const RasterLanes&) = delete;

  int lanes() const { return static_cast<int>(lanes_.size()); }
  bool pending() const { return queued_ > 0; }
  // Queue a triangle or a point drawn under `setup`. A setup different from the queued
  // primitives' (or a full queue) first flushes the queue into `pass`.
  void triangle(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c, const TriangleOptions& options,
                const FragmentStagesSetup& setup, Counters& pass);
  void point(const RasterVertex& v, double size, const FragmentStagesSetup& setup, Counters& pass);
  // Finish the queue; the lanes' counters are added to `pass`.
  void flush(Counters& pass);
  // Run task(lane) on the calling thread (lane 0) and on every worker lane that is free to
  // take it up before lane 0 has finished it: a worker does between two stretches of queued
  // jobs, so the task must not touch what rasterization reads or writes, and must be able to
  // do all its work on lane 0 alone (lanes claim parts of it). Returns when every lane that
  // took it is done; an exception a lane throws is rethrown here.
  void run_task(const std::function<void(int lane)>& task);

  // The lanes are woken for every this many queued primitives.
  static constexpr std::size_t kChunk = 64;
  // Bands of each cycle a worker lane takes (the calling thread takes one).
  static constexpr int kWorkerBands = 15;
  // A queue that ends shorter than a chunk runs on the calling thread alone (the same
  // result, without waking anyone). A queue this long is finished before more is added (bounds its memory).
  static constexpr std::size_t kMaxJobs = 4096;
  // Queues run on the lanes so far (for tests: the threads did run).
  static std::atomic<std::uint64_t> threaded_runs;
  // Tasks run on the lanes so far (for tests).
  static std::atomic<std::uint64_t> tasks_run;

 private:
  struct Job {
    RasterVertex v[3];
    TriangleOptions options;
    bool is_point = false;
    double point_size = 1.0;
  };
  using Lane = LaneStages;
  void add(const Job& job, const FragmentStagesSetup& setup, Counters& pass);
  void publish();
  void run_jobs(Lane& lane, const RasterTarget& target, std::size_t from, std::size_t to) const;
  RasterTarget lane_target(int index) const;
  void run_own_rows();  // lane 0's rows of the published jobs
  void worker(int index);

  std::unique_ptr<Job[]> jobs_;  // fixed storage: the lanes read earlier jobs while later ones are added
  std::size_t queued_ = 0;       // jobs in the queue (written by the calling thread only)
  std::size_t own_done_ = 0;     // jobs lane 0 has run on its rows
  FragmentStagesSetup setup_;    // of every queued job
  std::vector<std::unique_ptr<Lane>> lanes_;  // [0]: the calling thread's

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable work_, finished_;
  // Guarded by mutex_:
  std::size_t published_ = 0;  // jobs the lanes may run
  bool closing_ = false;       // the queue is complete: lanes report when they have run it
  std::uint64_t batch_ = 0;    // which queue (lanes reset their progress when it changes)
  int finished_lanes_ = 0;  // worker lanes done with a closing queue
  bool stop_ = false;
  std::exception_ptr error_;
  // run_task's, guarded by mutex_: the task (null once lane 0 is done with it), which one
  // (a lane takes each at most once), lanes running it.
  const std::function<void(int)>* task_ = nullptr;
  std::uint64_t task_serial_ = 0;
  int tasks_active_ = 0;
  std::exception_ptr task_error_;
};

}  // namespace passim
