// Telemetry CSV formatting and the writer thread. Rows are formatted into a stack buffer with
// snprintf, so the writer's cost is one fwrite per row and one fflush per drain.
#include "app/runtime/telemetry.hpp"

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cstring>
#include <stdexcept>

#include "app/runtime/realtime_setup.hpp"
#include "control/pose_tracker.hpp"
#include "estimator/pose_estimator.hpp"

namespace rovctl::app {
namespace {

class RowBuffer {
 public:
  RowBuffer(char* buf, std::size_t size) : buf_(buf), size_(size) {
    if (size_ > 0) buf_[0] = '\0';
  }
  template <class... Args>
  void put(const char* fmt, Args... args) {
    if (len_ + 1 >= size_) return;
    if (len_ > 0) append(",");
    const int n = std::snprintf(buf_ + len_, size_ - len_, fmt, args...);
    if (n > 0) len_ = std::min(size_ - 1, len_ + static_cast<std::size_t>(n));
  }
  void i64(std::int64_t v) { put("%" PRId64, v); }
  void u64(std::uint64_t v) { put("%" PRIu64, v); }
  void f(double v) { put("%.9g", v); }
  void us(std::int64_t ns) { put("%.3f", static_cast<double>(ns) * 1e-3); }
  std::size_t length() const { return len_; }

 private:
  void append(const char* s) {
    const int n = std::snprintf(buf_ + len_, size_ - len_, "%s", s);
    if (n > 0) len_ = std::min(size_ - 1, len_ + static_cast<std::size_t>(n));
  }
  char* buf_;
  std::size_t size_;
  std::size_t len_ = 0;
};

}  // namespace

void describe(hal::ParamVisitor& v, TelemetryParams& p) {
  v.param("enabled", p.enabled, "record one telemetry row per tick to CSV");
  v.param("ring_capacity", p.ring_capacity,
          {"records", 16, 1 << 20,
           "telemetry ring size between the tick and the writer thread (rounded up to a power of "
           "two); a full ring drops and counts records"});
  v.param("drain_period_ms", p.drain_period_ms,
          {"ms", 1.0, 10000.0, "how often the writer thread drains the ring to disk"});
}

void fill_schedule_fields(TelemetryRecord& r, const TickInfo& tick,
                          const CyclicScheduler& scheduler) noexcept {
  r.tick = tick.index;
  r.release = tick.release;
  r.time_s = tick.time_s();
  r.deadline_ns = tick.deadline.count();
  r.wakeup_ns = tick.wakeup.count();
  for (std::size_t i = 0; i < kStageCount; ++i) {
    r.stage_ns[i] = scheduler.stage_time(static_cast<Stage>(i)).count();
  }
  r.skipped_total = tick.skipped_total;
  if (tick.skipped_before > 0) r.flags |= telemetry_flag::overrun;
  if (scheduler.over_budget_mask() != 0) r.flags |= telemetry_flag::stage_over_budget;
}

const char* telemetry_csv_header() noexcept {
  return "tick,release,time_s,deadline_ns,wakeup_ns,jitter_us,capture_ns,"
         "capture_us,segment_us,estimate_us,control_us,actuate_us,telemetry_us,skipped_total,"
         "mission_state,generations,fitness,spheres_left,spheres_right,"
         "error_bound_m,error_bound_deg,not_ok_reason,"
         "est_x_m,est_y_m,est_z_m,est_qw,est_qx,est_qy,est_qz,"
         "truth_x_m,truth_y_m,truth_z_m,truth_qw,truth_qx,truth_qy,truth_qz,"
         "est_error_m,est_error_rad,"
         "err_x_m,err_y_m,err_z_m,err_rx_rad,err_ry_rad,err_rz_rad,"
         "dock_lateral_m,dock_axial_m,dock_yaw_rad,"
         "fx_n,fy_n,fz_n,mx_nm,my_nm,mz_nm,"
         "thruster_count,cmd0,cmd1,cmd2,cmd3,cmd4,cmd5,cmd6,cmd7,"
         "bus_status,flags,push_est_x_n,push_est_y_n,push_truth_x_n,push_truth_y_n,"
         "track_source,track_bound_m,track_bound_deg,"
         "track_x_m,track_y_m,track_z_m,track_qw,track_qx,track_qy,track_qz,"
         "track_error_m,track_error_rad";
}

std::size_t format_telemetry_csv_row(const TelemetryRecord& r, char* buf,
                                     std::size_t size) noexcept {
  RowBuffer row(buf, size);
  row.u64(r.tick);
  row.u64(r.release);
  row.put("%.6f", r.time_s);
  row.i64(r.deadline_ns);
  row.i64(r.wakeup_ns);
  row.us(r.wakeup_ns - r.deadline_ns);
  row.i64(r.capture_ns);
  for (const std::int64_t ns : r.stage_ns) row.us(ns);
  row.u64(r.skipped_total);
  row.i64(r.mission_state);
  row.i64(r.generations);
  row.f(r.fitness);
  row.i64(r.spheres_seen_left);
  row.i64(r.spheres_seen_right);
  row.f(r.error_bound_m);
  row.f(r.error_bound_deg);
  row.put("%s", estimator::to_string(static_cast<estimator::NotOkReason>(r.not_ok_reason)));
  for (const double v : r.est_t_m) row.f(v);
  for (const double v : r.est_q_wxyz) row.f(v);
  for (const double v : r.truth_t_m) row.f(v);
  for (const double v : r.truth_q_wxyz) row.f(v);
  row.f(r.est_error_m);
  row.f(r.est_error_rad);
  for (const double v : r.pose_error) row.f(v);
  row.f(r.dock_lateral_error_m);
  row.f(r.dock_axial_error_m);
  row.f(r.dock_yaw_error_rad);
  for (const double v : r.wrench_body) row.f(v);
  row.i64(r.thruster_count);
  for (const double v : r.thruster_cmd) row.f(v);
  row.i64(r.bus_status);
  row.u64(r.flags);
  for (const double v : r.push_est_n) row.f(v);
  for (const double v : r.push_truth_n) row.f(v);
  row.put("%s", control::to_string(static_cast<control::TrackSource>(r.track_source)));
  row.f(r.track_bound_m);
  row.f(r.track_bound_deg);
  for (const double v : r.track_t_m) row.f(v);
  for (const double v : r.track_q_wxyz) row.f(v);
  row.f(r.track_error_m);
  row.f(r.track_error_rad);
  return row.length();
}

TelemetryWriter::TelemetryWriter(TelemetryRing& ring, std::string path,
                                 std::chrono::milliseconds drain_period)
    : ring_(ring), path_(std::move(path)), tmp_path_(path_ + ".tmp"), drain_period_(drain_period) {}

TelemetryWriter::~TelemetryWriter() {
  try {
    stop();
  } catch (...) {
    // Reported by an explicit stop(); a destructor must not throw.
  }
}

void TelemetryWriter::start() {
  if (thread_.joinable()) return;
  file_ = std::fopen(tmp_path_.c_str(), "w");
  if (file_ == nullptr) {
    throw std::runtime_error("telemetry: cannot create " + tmp_path_ + ": " + std::strerror(errno));
  }
  if (std::fprintf(file_, "%s\n", telemetry_csv_header()) < 0) write_error_ = true;
  stopping_ = false;
  thread_ = std::thread([this] { loop(); });
}

void TelemetryWriter::stop() {
  if (!thread_.joinable() && file_ == nullptr) return;
  if (thread_.joinable()) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  drain();  // whatever the producer pushed after the thread's last pass
  if (std::fflush(file_) != 0) write_error_ = true;
  if (std::fclose(file_) != 0) write_error_ = true;
  file_ = nullptr;
  if (write_error_) {
    throw std::runtime_error("telemetry: write to " + tmp_path_ + " failed (disk full?)");
  }
  if (std::rename(tmp_path_.c_str(), path_.c_str()) != 0) {
    throw std::runtime_error("telemetry: cannot rename " + tmp_path_ + " to " + path_ + ": " +
                             std::strerror(errno));
  }
}

void TelemetryWriter::loop() {
  make_thread_non_realtime();
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    wake_.wait_for(lock, drain_period_, [this] { return stopping_; });
    lock.unlock();
    drain();
    if (std::fflush(file_) != 0) write_error_ = true;
    lock.lock();
  }
}

void TelemetryWriter::drain() {
  TelemetryRecord r;
  char buf[2048];
  while (ring_.try_pop(r)) {
    const std::size_t n = format_telemetry_csv_row(r, buf, sizeof buf - 1);
    buf[n] = '\n';
    if (std::fwrite(buf, 1, n + 1, file_) != n + 1) write_error_ = true;
    rows_.fetch_add(1, std::memory_order_relaxed);
  }
}

}  // namespace rovctl::app
