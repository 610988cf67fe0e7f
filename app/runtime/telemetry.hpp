// Telemetry: one fixed-size record per tick, pushed by the tick into a lock-free ring and written
// to CSV by a non-real-time thread, so disk latency never reaches the control loop.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>

#include "app/runtime/cyclic_scheduler.hpp"
#include "hal/interfaces/thruster_bus.hpp"
#include "hal/primitives/parameters.hpp"
#include "hal/primitives/spsc_ring.hpp"

namespace rovctl::app {

struct TelemetryParams {
  bool enabled = true;
  int ring_capacity = 1024;  // records; rounded up to a power of two
  double drain_period_ms = 100.0;
};

void describe(hal::ParamVisitor& v, TelemetryParams& p);

// TelemetryRecord::flags bits.
namespace telemetry_flag {
constexpr std::uint32_t truth_valid = 1u << 0;        // truth_* fields hold the simulator's pose
constexpr std::uint32_t estimate_valid = 1u << 1;     // est_* hold a pose estimate
constexpr std::uint32_t recognised = 1u << 2;         // fitness at or above the threshold
constexpr std::uint32_t overrun = 1u << 3;            // releases were skipped before this tick
constexpr std::uint32_t stage_over_budget = 1u << 4;  // some stage exceeded its budget
constexpr std::uint32_t capture_failed = 1u << 5;
constexpr std::uint32_t armed = 1u << 6;
constexpr std::uint32_t failsafe = 1u << 7;
constexpr std::uint32_t dock_errors_valid = 1u << 8;  // dock_* hold the mission's axis errors
constexpr std::uint32_t full_view = 1u << 9;       // the estimate is ok: every sphere in both views
constexpr std::uint32_t operator_hold = 1u << 10;  // the operator aborted: neutral until START
constexpr std::uint32_t current_settled = 1u << 11;  // the servo's estimate of the current settled
// The pose tracker is on: the mission acts on track_*, not est_*.
constexpr std::uint32_t tracking = 1u << 12;
constexpr std::uint32_t track_ok = 1u << 13;  // the tracked pose is ok (bounds within the limits)
}  // namespace telemetry_flag

// One tick. Poses are T_cl_marker (marker in the left camera frame): translation in m, unit
// quaternion w, x, y, z. Fields not known in a tick stay NaN (doubles) or 0.
struct TelemetryRecord {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  std::uint64_t tick = 0;
  std::uint64_t release = 0;
  double time_s = 0.0;  // release time since the run started
  std::int64_t deadline_ns = 0;
  std::int64_t wakeup_ns = 0;
  std::int64_t capture_ns = 0;  // camera capture stamp (left), 0 if none
  std::array<std::int64_t, kStageCount> stage_ns{};
  std::uint64_t skipped_total = 0;  // releases skipped so far in the run

  std::int32_t mission_state = 0;  // control's mission state id
  std::int32_t generations = 0;    // RM-GA generations this tick
  double fitness = kNaN;
  std::int32_t spheres_seen_left = 0, spheres_seen_right = 0;
  double error_bound_m = kNaN;    // translation error bound of the estimate, when refined
  double error_bound_deg = kNaN;  // its rotation error bound, when refined
  // Why a recognised estimate is not trusted (estimator::NotOkReason as int; 0, none, when ok or
  // not recognised). Written as its token, so the CSV says "bound_over_limit", not a number.
  std::int32_t not_ok_reason = 0;
  std::array<double, 3> est_t_m{kNaN, kNaN, kNaN};
  std::array<double, 4> est_q_wxyz{kNaN, kNaN, kNaN, kNaN};
  std::array<double, 3> truth_t_m{kNaN, kNaN, kNaN};
  std::array<double, 4> truth_q_wxyz{kNaN, kNaN, kNaN, kNaN};
  double est_error_m = kNaN;    // |estimate - truth| translation
  double est_error_rad = kNaN;  // rotation angle between estimate and truth
  // Servo error (desired minus estimated relative pose): x, y, z in m, rotation vector in rad.
  std::array<double, 6> pose_error{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
  // The probe's error against the docking axis (the mission's view): lateral off the axis, axial
  // along it (negative: short of docked), yaw of the axis in body x-y.
  double dock_lateral_error_m = kNaN;
  double dock_axial_error_m = kNaN;
  double dock_yaw_error_rad = kNaN;
  std::array<double, 6> wrench_body{};                    // Fx, Fy, Fz (N), Mx, My, Mz (N m)
  std::array<double, hal::kMaxThrusters> thruster_cmd{};  // fraction of full thrust, [-1, 1]
  std::int32_t thruster_count = 0;
  std::int32_t bus_status = 0;  // hal::BusStatus as int
  std::uint32_t flags = 0;      // telemetry_flag bits
  // The water's push on the vehicle, body x and y (N): as the servo estimates it (the negated
  // integral term), and in the sim the truth (the current's drag on a vehicle at rest).
  std::array<double, 2> push_est_n{kNaN, kNaN};
  std::array<double, 2> push_truth_n{kNaN, kNaN};
  // The pose tracked across frames (control::PoseTracker): where it came from this tick
  // (control::TrackSource as int, written as its token), its bounds and pose (NaN with no track),
  // and in the sim its error against the truth at the frame's capture.
  std::int32_t track_source = 0;
  double track_bound_m = kNaN;
  double track_bound_deg = kNaN;
  std::array<double, 3> track_t_m{kNaN, kNaN, kNaN};
  std::array<double, 4> track_q_wxyz{kNaN, kNaN, kNaN, kNaN};
  double track_error_m = kNaN;
  double track_error_rad = kNaN;
};
static_assert(std::is_trivially_copyable_v<TelemetryRecord>);
static_assert(std::is_standard_layout_v<TelemetryRecord>);

// Fills the scheduling fields (tick, release, stamps, stage times so far, skips, overrun flags).
void fill_schedule_fields(TelemetryRecord& r, const TickInfo& tick,
                          const CyclicScheduler& scheduler) noexcept;

using TelemetryRing = SpscRing<TelemetryRecord>;

// CSV header line (no newline) and one row; the row goes into `buf` without allocating,
// returning its length (truncated rows are cut at `size - 1`).
const char* telemetry_csv_header() noexcept;
std::size_t format_telemetry_csv_row(const TelemetryRecord& r, char* buf,
                                     std::size_t size) noexcept;

// Drains a ring into a CSV file on its own (SCHED_OTHER) thread. Writes `<path>.tmp` and renames
// it to `path` on stop(), so a crash never leaves a half-written file under the final name.
class TelemetryWriter {
 public:
  TelemetryWriter(TelemetryRing& ring, std::string path,
                  std::chrono::milliseconds drain_period = std::chrono::milliseconds(100));
  ~TelemetryWriter();  // stop(), errors swallowed
  TelemetryWriter(const TelemetryWriter&) = delete;
  TelemetryWriter& operator=(const TelemetryWriter&) = delete;

  // Opens the file and starts the thread; throws std::runtime_error naming the file.
  void start();
  // Drains what is left, joins, closes and renames; throws std::runtime_error naming the file on
  // a write error. Idempotent.
  void stop();

  std::uint64_t rows_written() const noexcept { return rows_.load(std::memory_order_relaxed); }
  const std::string& path() const noexcept { return path_; }

 private:
  void loop();
  void drain();

  TelemetryRing& ring_;
  std::string path_;
  std::string tmp_path_;
  std::chrono::milliseconds drain_period_;
  std::FILE* file_ = nullptr;
  std::thread thread_;
  std::mutex mutex_;  // only between the writer thread and stop(); the producer never takes it
  std::condition_variable wake_;
  bool stopping_ = false;
  bool write_error_ = false;
  std::atomic<std::uint64_t> rows_{0};
};

}  // namespace rovctl::app
