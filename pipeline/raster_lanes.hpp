// Rasterization and the fragment stages on several threads, bit-identical to one thread
// (docs/threads.md). The calling thread transforms, lights and clips, and queues each
// primitive with the stage setup it was drawn under; the lanes rasterize the queue as it
// grows. The window's rows are dealt out to row groups: stripes of kStripeRows rows, group g
// holding the stripes whose index is g modulo the number of groups. A lane that is free
// claims a group nobody holds that has queued primitives it has not run, and runs them, in
// order, over that group's rows only; the calling thread (lane 0) joins in whenever it has
// queued a chunk. So a pixel is written by the same primitives in the same order with the
// same arithmetic as on one thread, whichever lane ran them; the counters are sums of
// integers, which do not depend on the order of adding. Claiming rather than a fixed share
// keeps both cores busy when one is slower (the calling thread's vertex work, or a core
// that the host shares).
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "stages/fragment_stages.hpp"
#include "stages/line_rasterizer.hpp"

namespace passim {

// A triangle a display-list block assembled (Context::draw_triangle_batch): its window
// vertices, the colour flat shading gives it, and the block's triangle it comes from. Its
// rows on the window (triangle_rows) are found while assembling, on every lane, and kept
// apart, 8 bytes a triangle: a row group holding none of them passes it over without
// reading it (pass_over_triangle), let alone setting it up.
struct AssembledTriangle {
  AssembledTriangle(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c, const Vec4& flat,
                    std::size_t from)
      : v{a, b, c}, flat_color(flat), source(from) {}
  RasterVertex v[3];
  Vec4 flat_color;
  std::size_t source;
};

// Chunks [0, count) shared out among `lanes` lanes of a run_task: lane k claims chunks from
// its own share, the k-th of `lanes` contiguous shares, in order, then from the shares after
// it. Two tasks over related ranges (a display-list block's distinct vertices and its
// triangles, which use vertices numbered near their own position) then give each lane mostly
// the data it made itself, while a lane that is faster still takes over another's share.
class ChunkClaims {
 public:
  ChunkClaims(std::size_t count, int lanes);
  // The next chunk for `lane`, or count() when none is left.
  std::size_t next(int lane);
  std::size_t count() const { return count_; }

 private:
  struct alignas(64) Share {
    std::atomic<std::size_t> next{0};
    std::size_t end = 0;
  };
  std::size_t count_;
  int lanes_;
  std::unique_ptr<Share[]> shares_;
};

class RasterLanes {
 public:
  // `lanes` >= 2: the calling thread and lanes − 1 workers.
  RasterLanes(Framebuffer& fb, int lanes);
  ~RasterLanes();
  RasterLanes(const RasterLanes&) = delete;
  RasterLanes& operator=(const RasterLanes&) = delete;

  int lanes() const { return static_cast<int>(lanes_.size()); }
  bool pending() const { return queued_ > 0; }
  // Queue a triangle, a point or a line segment drawn under `setup`. A setup different from the queued
  // primitives' (or a full queue) first flushes the queue into `pass`.
  void triangle(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c, const TriangleOptions& options,
                const FragmentStagesSetup& setup, Counters& pass);
  void point(const RasterVertex& v, double size, const FragmentStagesSetup& setup, Counters& pass);
  void line(const RasterVertex& a, const RasterVertex& b, const TriangleOptions& attributes,
            const LineOptions& options, const FragmentStagesSetup& setup, Counters& pass);
  // Queue `count` triangles drawn with `options` but each its own flat colour, by reference:
  // they must stay as they are until the queue is run (queue_serial() has moved on, or
  // pending() is false).
  void triangles(const AssembledTriangle* first, const TriangleRows* rows, std::size_t count,
                 const TriangleOptions& options, const FragmentStagesSetup& setup, Counters& pass);
  // How make_caches may split its work over the lanes when a queue starts (nothing is
  // rasterizing then): Context::rows_on_lanes, which runs tasks on these lanes.
  void set_row_splitter(const RowSplitter* split) { row_splitter_ = split; }
  // Which queue is being filled: it changes when a queue has been run.
  std::uint64_t queue_serial() const { return batch_; }
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
  // Rows of a stripe, and row groups per lane (more groups than lanes, so that a lane never
  // waits for a group while another has work; few, since a primitive across several groups'
  // rows is set up once in each).
  static constexpr int kStripeRows = 32;
  static constexpr int kGroupsPerLane = 2;
  // While it queues, the calling thread runs a group only when the group is this many jobs
  // behind (the workers keep up otherwise; at the end of a queue it runs whatever is left).
  static constexpr std::size_t kHelpBacklog = 1024;
  // How long a lane with nothing to do watches for work before it sleeps (see wait).
  static constexpr std::chrono::microseconds kSpin{200};
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
    const AssembledTriangle* run = nullptr;  // triangles queued by reference: v unused
    const TriangleRows* run_rows = nullptr;  // their rows
    std::size_t run_count = 0;
    bool is_line = false;  // v[0] → v[1] with options (its attributes) and line_options
    LineOptions line_options{};
  };
  using Lane = LaneStages;
  // A row group's progress through the published jobs.
  struct Group {
    std::size_t done = 0;  // jobs run over its rows
    bool busy = false;     // a lane is running it
  };
  // Queue a job of `primitives` primitives; the lanes are woken at every kChunk primitives.
  void add(const Job& job, std::size_t primitives, const FragmentStagesSetup& setup, Counters& pass);
  void run_jobs(Lane& lane, const RasterTarget& target, std::size_t from, std::size_t to) const;
  RasterTarget group_target(int group) const;
  // With mutex_ held: a group nobody holds with published jobs it has not run (searched from
  // `from`), or −1; and whether every group has run every published job.
  int claimable(int from, std::size_t backlog = 1) const;
  bool all_run() const;
  // Lane `index` claims and runs groups until none is claimable; `lock` holds mutex_.
  void run_groups(int index, std::unique_lock<std::mutex>& lock, std::size_t backlog = 1);
  void worker(int index);
  // Every change a waiting lane may be waiting for is announced through notify; wait spins
  // on the announcements for up to kSpin before sleeping on the condition variable (waking a
  // sleeping thread takes up to a millisecond on a virtual machine, more than a chunk's work).
  void notify(std::condition_variable& cv);
  template <class Ready>
  void wait(std::unique_lock<std::mutex>& lock, std::condition_variable& cv, Ready ready);

  const RowSplitter* row_splitter_ = nullptr;
  // The row group of each stripe of the window (stripe b: group b mod the groups).
  std::vector<std::uint16_t> stripe_groups_;
  std::unique_ptr<Job[]> jobs_;  // fixed storage: the lanes read earlier jobs while later ones are added
  std::size_t queued_ = 0;       // jobs in the queue (written by the calling thread only)
  std::size_t primitives_ = 0;   // primitives in those jobs (likewise)
  FragmentStagesSetup setup_;    // of every queued job
  std::vector<std::unique_ptr<Lane>> lanes_;  // [0]: the calling thread's
  // The queue each lane's stages are connected for (only that lane touches its entry).
  std::vector<std::uint64_t> lane_batch_;

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::atomic<std::uint64_t> announcements_{0};
  std::condition_variable work_, finished_;
  // Guarded by mutex_:
  std::vector<Group> groups_;
  std::size_t published_ = 0;  // jobs the lanes may run
  std::uint64_t batch_ = 1;    // which queue (a lane reconnects its stages when it changes)
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
