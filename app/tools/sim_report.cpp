// Summary statistics, CSV and plots of docking trials.
#include "app/tools/sim_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "app/tools/atomic_file.hpp"
#include "app/tools/json_writer.hpp"
#include "app/tools/plot.hpp"
#include "app/tools/validation_set.hpp"
#include "control/mission.hpp"
#include "hal/primitives/percentile.hpp"

namespace rovctl::app {
namespace {

// Reports write -1 for a figure with no samples (no trial docked).
double percentile_or_none(const std::vector<double>& v, double p) {
  return v.empty() ? -1.0 : hal::percentile(v, p);
}

void summarise_recharge(const std::vector<TrialResult>& results, SimSummary& s) {
  std::vector<double> contact, seated_h, hold_wh, charged_wh, hold_fraction, clearance;
  for (const TrialResult& r : results) {
    if (!r.recharge) continue;
    s.recharge = true;
    const RechargeResult& c = r.charge;
    if (trial_recharged(r)) ++s.recharged;
    if (c.charged) ++s.charged;
    if (c.departed) ++s.departed;
    if (c.departed && c.undock_marker_in_view) ++s.undock_clear;
    s.reseats += c.reseats;
    s.unseated_unnoticed_max_s = std::max(s.unseated_unnoticed_max_s, c.unseated_unnoticed_max_s);
    if (c.charging_reached) {
      contact.push_back(c.contact_fraction);
      seated_h.push_back(c.seated_s / 3600.0);
      hold_wh.push_back(c.hold_wh);
      charged_wh.push_back(c.charged_wh);
      if (c.charged_wh > 0.0) hold_fraction.push_back(c.hold_fraction);
    }
    if (c.departed) clearance.push_back(c.undock_clearance_m);
  }
  if (!s.recharge) return;
  s.recharge_rate = s.trials > 0 ? static_cast<double>(s.recharged) / s.trials : 0.0;
  s.contact_fraction_min =
      contact.empty() ? -1.0 : *std::min_element(contact.begin(), contact.end());
  s.contact_fraction_median = percentile_or_none(contact, 0.5);
  s.seated_h_median = percentile_or_none(seated_h, 0.5);
  s.hold_wh_median = percentile_or_none(hold_wh, 0.5);
  s.charged_wh_median = percentile_or_none(charged_wh, 0.5);
  s.hold_fraction_median = percentile_or_none(hold_fraction, 0.5);
  s.hold_fraction_max =
      hold_fraction.empty() ? -1.0 : *std::max_element(hold_fraction.begin(), hold_fraction.end());
  s.undock_clearance_m_min =
      clearance.empty() ? -1.0 : *std::min_element(clearance.begin(), clearance.end());
}

std::string fixed(double v, int decimals) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, v);
  return text;
}

// The text reports' form of a figure the JSON writes as -1 when there is no sample (no trial
// docked, charged or departed): "none" in a summary, "-" in a trial's row, never a number. Only
// for figures that are never negative; a signed one (yaw) says "none" by its own condition.
std::string figure(double v, int decimals, const char* none = "none", double scale = 1.0) {
  return v < 0.0 ? none : fixed(scale * v, decimals);
}

}  // namespace

SimSummary summarise(const std::vector<TrialResult>& results) {
  SimSummary s;
  s.trials = static_cast<int>(results.size());
  std::vector<double> times, lateral, yaw, est_err, frame_cpu;
  double estimator_ms = 0.0;
  for (const TrialResult& r : results) {
    if (r.docked) ++s.captured;
    if (trial_docked(r)) ++s.docked;  // never the cached flag alone: the mission must say DOCKED
    if (r.docked) {
      times.push_back(r.time_to_dock_s);
      lateral.push_back(r.lateral_error_mm);
      yaw.push_back(std::abs(r.yaw_error_deg));
    }
    if (r.estimate_error_mm_median >= 0) est_err.push_back(r.estimate_error_mm_median);
    if (r.touch_lateral_max_mm > kTouchOffCentreMm) ++s.touched_off_centre;
    s.touch_lateral_mm_max = std::max(s.touch_lateral_mm_max, r.touch_lateral_max_mm);
    s.ticks += r.ticks;
    s.overruns += r.overruns;
    s.tick_jitter_ms_p99 = std::max(s.tick_jitter_ms_p99, r.jitter_p99_ms);
    s.tick_jitter_ms_max = std::max(s.tick_jitter_ms_max, r.jitter_max_ms);
    estimator_ms += r.estimator_ms_mean;
    s.ok_ticks += r.ok_ticks;
    s.ok_wrong_ticks += r.ok_wrong_ticks;
    s.ok_over_bound_ticks += r.ok_over_bound_ticks;
    if (r.ok_wrong_ticks > 0) ++s.trials_ok_wrong;
    s.ok_error_mm_max = std::max(s.ok_error_mm_max, r.ok_error_mm_max);
    s.ok_error_deg_max = std::max(s.ok_error_deg_max, r.ok_error_deg_max);
    s.ok_carried_ticks += r.ok_carried_ticks;
    frame_cpu.push_back(r.frame_cpu_ms_p95);
    s.frame_cpu_ms_p95_max = std::max(s.frame_cpu_ms_p95_max, r.frame_cpu_ms_p95);
  }
  s.frame_cpu_ms_p95_median = frame_cpu.empty() ? 0.0 : hal::percentile(frame_cpu, 0.5);
  s.success_rate = s.trials > 0 ? static_cast<double>(s.docked) / s.trials : 0.0;
  s.time_to_dock_s_median = percentile_or_none(times, 0.5);
  s.final_lateral_error_mm_p95 = percentile_or_none(lateral, 0.95);
  s.final_yaw_error_deg_p95 = percentile_or_none(yaw, 0.95);
  s.estimator_ms_mean = s.trials > 0 ? estimator_ms / s.trials : 0.0;
  s.estimate_error_mm_median = percentile_or_none(est_err, 0.5);
  summarise_recharge(results, s);
  return s;
}

std::string summary_json(const SimSummary& s) {
  JsonWriter j;
  j.begin_object()
      .field("trials", s.trials)
      .field("docked", s.docked)
      .field("success_rate", s.success_rate)
      .field("time_to_dock_s_median", s.time_to_dock_s_median)
      .field("final_lateral_error_mm_p95", s.final_lateral_error_mm_p95)
      .field("final_yaw_error_deg_p95", s.final_yaw_error_deg_p95)
      .field("overruns", static_cast<long>(s.overruns))
      .field("tick_jitter_ms_p99", s.tick_jitter_ms_p99)
      .field("captured", s.captured)
      .field("touched_off_centre", s.touched_off_centre)
      .field("touch_lateral_mm_max", s.touch_lateral_mm_max)
      .field("ticks", static_cast<long>(s.ticks))
      .field("tick_jitter_ms_max", s.tick_jitter_ms_max)
      .field("estimator_ms_mean", s.estimator_ms_mean)
      .field("estimate_error_mm_median", s.estimate_error_mm_median)
      .field("ok_ticks", static_cast<long>(s.ok_ticks))
      .field("ok_wrong_ticks", static_cast<long>(s.ok_wrong_ticks))
      .field("trials_ok_wrong", s.trials_ok_wrong)
      .field("ok_over_bound_ticks", static_cast<long>(s.ok_over_bound_ticks))
      .field("ok_error_mm_max", s.ok_error_mm_max)
      .field("ok_error_deg_max", s.ok_error_deg_max)
      .field("ok_carried_ticks", static_cast<long>(s.ok_carried_ticks))
      .field("frame_cpu_ms_p95_median", s.frame_cpu_ms_p95_median)
      .field("frame_cpu_ms_p95_max", s.frame_cpu_ms_p95_max);
  if (s.recharge) {
    j.begin_object("recharge")
        .field("recharged", s.recharged)
        .field("recharge_rate", s.recharge_rate)
        .field("charged", s.charged)
        .field("departed", s.departed)
        .field("undock_clear_marker_in_view", s.undock_clear)
        .field("contact_fraction_min", s.contact_fraction_min)
        .field("contact_fraction_median", s.contact_fraction_median)
        .field("unseated_unnoticed_max_s", s.unseated_unnoticed_max_s)
        .field("reseats", s.reseats)
        .field("seated_h_median", s.seated_h_median)
        .field("hold_wh_median", s.hold_wh_median)
        .field("charged_wh_median", s.charged_wh_median)
        .field("hold_fraction_median", s.hold_fraction_median)
        .field("hold_fraction_max", s.hold_fraction_max)
        .field("undock_clearance_m_min", s.undock_clearance_m_min)
        .end_object();
  }
  j.end_object();
  return j.str();
}

std::string summary_text(const SimSummary& s, const std::vector<TrialResult>& results) {
  std::ostringstream o;
  char line[768];
  o << "trial  start_m  current_mps  result     state    aborts  t_dock_s  lateral_mm  yaw_deg  "
       "est_err_mm\n";
  for (const TrialResult& r : results) {
    std::snprintf(line, sizeof(line), "%5d  %7.2f  %11.3f  %-9s  %-7s  %6d  %8s  %10s  %7s  %10s\n",
                  r.conditions.index, r.conditions.distance_m,
                  r.conditions.current_mean_world_mps.norm(),
                  trial_docked(r) ? "DOCKED" : (r.docked ? "off-tol" : "no dock"),
                  r.final_state.c_str(), r.aborts, figure(r.time_to_dock_s, 1, "-").c_str(),
                  figure(r.lateral_error_mm, 1, "-").c_str(),
                  r.docked ? fixed(r.yaw_error_deg, 2).c_str() : "-",
                  figure(r.estimate_error_mm_median, 1, "-").c_str());
    o << line;
  }
  std::snprintf(
      line, sizeof(line),
      "\ndocked %d of %d (%.0f %%)  time to dock median %s s  lateral error p95 %s mm  "
      "yaw error p95 %s deg\ntouched the station over %.0f mm off the axis: %d trials "
      "(largest touch %s mm)\nticks %llu  overruns %llu  tick jitter p99 %.3f ms (max %.3f)  "
      "estimator %.2f ms per tick  estimate error median %s mm\nok estimates %llu ticks, ok "
      "but wrong (>= %.0f mm or %.0f deg from their image's truth) %llu in %d trials (worst ok "
      "%.1f mm, %.2f deg); off by more than their own error bound %llu\n",
      s.docked, s.trials, 100.0 * s.success_rate, figure(s.time_to_dock_s_median, 1).c_str(),
      figure(s.final_lateral_error_mm_p95, 1).c_str(), figure(s.final_yaw_error_deg_p95, 2).c_str(),
      kTouchOffCentreMm, s.touched_off_centre, figure(s.touch_lateral_mm_max, 1).c_str(),
      static_cast<unsigned long long>(s.ticks), static_cast<unsigned long long>(s.overruns),
      s.tick_jitter_ms_p99, s.tick_jitter_ms_max, s.estimator_ms_mean,
      figure(s.estimate_error_mm_median, 1).c_str(), static_cast<unsigned long long>(s.ok_ticks),
      kRightTranslationMm, kRightRotationDeg, static_cast<unsigned long long>(s.ok_wrong_ticks),
      s.trials_ok_wrong, s.ok_error_mm_max, s.ok_error_deg_max,
      static_cast<unsigned long long>(s.ok_over_bound_ticks));
  o << line;
  std::snprintf(line, sizeof(line),
                "ok ticks the pose tracker carried through a frame it could not fuse %llu; frame "
                "processor time p95 %.2f ms (median trial), %.2f ms (worst trial)\n",
                static_cast<unsigned long long>(s.ok_carried_ticks), s.frame_cpu_ms_p95_median,
                s.frame_cpu_ms_p95_max);
  o << line;
  if (s.recharge) {
    o << "\ntrial  result      end of charge                          seated_h  contact  "
         "unseated_max_s  reseats  hold_Wh  charged_Wh  hold_%  soc       clearance_m  marker\n";
    for (const TrialResult& r : results) {
      const RechargeResult& c = r.charge;
      std::snprintf(line, sizeof(line),
                    "%5d  %-10s  %-37.37s  %8.2f  %7.4f  %14.2f  %7d  %7.1f  %10.1f  %6.2f  "
                    "%.2f-%.2f  %11s  %s\n",
                    r.conditions.index, trial_recharged(r) ? "RECHARGED" : r.final_state.c_str(),
                    c.end_reason.empty() ? "-" : c.end_reason.c_str(), c.seated_s / 3600.0,
                    c.contact_fraction, c.unseated_unnoticed_max_s, c.reseats, c.hold_wh,
                    c.charged_wh, 100.0 * c.hold_fraction, c.soc_start, c.soc_end,
                    figure(c.undock_clearance_m, 3, "-").c_str(),
                    c.undock_marker_in_view ? "in view" : "-");
      o << line;
    }
    std::snprintf(line, sizeof(line),
                  "\nrecharged (docked, charged, departed) %d of %d (%.0f %%)  charged %d  "
                  "departed %d  clear with marker in view %d\ncontact held min %s (median "
                  "%s) of the charging time  longest unnoticed unseat %.2f s  re-seats %d\n"
                  "seated median %s h  hold energy median %s Wh of %s Wh charged  hold/charged "
                  "median %s %% (max %s %%)  undock clearance min %s m\n",
                  s.recharged, s.trials, 100.0 * s.recharge_rate, s.charged, s.departed,
                  s.undock_clear, figure(s.contact_fraction_min, 4).c_str(),
                  figure(s.contact_fraction_median, 4).c_str(), s.unseated_unnoticed_max_s,
                  s.reseats, figure(s.seated_h_median, 2).c_str(),
                  figure(s.hold_wh_median, 1).c_str(), figure(s.charged_wh_median, 1).c_str(),
                  figure(s.hold_fraction_median, 2, "none", 100.0).c_str(),
                  figure(s.hold_fraction_max, 2, "none", 100.0).c_str(),
                  figure(s.undock_clearance_m_min, 3).c_str());
    o << line;
  }
  return o.str();
}

void plot_trial(const TrialResult& trial, const std::string& png_path) {
  const auto& recs = trial.records;
  std::vector<double> t;
  std::vector<double> est[3], truth[3], perr[4], fitness, state, err_mm, err_deg;
  std::vector<double> push_est[2], push_truth[2];
  std::vector<double> thr[hal::kMaxThrusters];
  const int n_thr = recs.empty() ? 0 : recs.front().thruster_count;
  for (const TelemetryRecord& r : recs) {
    t.push_back(r.time_s);
    const bool has_est = (r.flags & telemetry_flag::recognised) != 0;
    for (int i = 0; i < 3; ++i) {
      est[i].push_back(has_est ? r.est_t_m[i] : NAN);
      truth[i].push_back(r.truth_t_m[i]);
    }
    for (int i = 0; i < 3; ++i) perr[i].push_back(r.pose_error[i] * 1000.0);
    perr[3].push_back(r.pose_error[5] * 180.0 / M_PI);
    for (int i = 0; i < 2; ++i) {
      push_est[i].push_back(r.push_est_n[i]);
      push_truth[i].push_back(r.push_truth_n[i]);
    }
    fitness.push_back(r.fitness);
    err_mm.push_back(has_est ? r.est_error_m * 1000.0 : NAN);
    err_deg.push_back(has_est ? r.est_error_rad * 180.0 / M_PI : NAN);
    state.push_back(r.mission_state);
    for (int i = 0; i < n_thr; ++i) thr[i].push_back(r.thruster_cmd[i]);
  }
  char title[256];
  std::snprintf(title, sizeof(title),
                "Docking trial %d: start %.2f m, current %.3f m/s -> %s (lateral %.1f mm, yaw %.2f "
                "deg, %.1f s)",
                trial.conditions.index, trial.conditions.distance_m,
                trial.conditions.current_mean_world_mps.norm(),
                trial_docked(trial) ? "DOCKED" : trial.final_state.c_str(), trial.lateral_error_mm,
                trial.yaw_error_deg, trial.time_to_dock_s);
  if (trial.recharge) {
    const RechargeResult& c = trial.charge;
    std::snprintf(title, sizeof(title),
                  "Recharge trial %d: start %.2f m, current %.3f m/s -> %s (docked %.1f s, seated "
                  "%.2f h, hold %.1f Wh of %.1f Wh charged, re-seats %d)",
                  trial.conditions.index, trial.conditions.distance_m,
                  trial.conditions.current_mean_world_mps.norm(),
                  trial_recharged(trial) ? "RECHARGED" : trial.final_state.c_str(),
                  trial.time_to_dock_s, c.seated_s / 3600.0, c.hold_wh, c.charged_wh, c.reseats);
  }
  Plot plot(title, 1400);
  auto& p1 = plot.add_panel("Marker position in the left camera: estimate vs truth", "time [s]",
                            "position [m]");
  const char* axis[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    p1.line(std::string("truth ") + axis[i], t, truth[i]);
    p1.line(std::string("estimate ") + axis[i], t, est[i]);
  }
  auto& p2 =
      plot.add_panel("Estimation error (while recognised)", "time [s]", "error [mm] / [deg]");
  p2.line("translation [mm]", t, err_mm).line("rotation [deg]", t, err_deg);
  auto& p3 = plot.add_panel("Servo pose error (body frame, desired - estimated)", "time [s]",
                            "[mm] / [deg]");
  p3.line("x fwd [mm]", t, perr[0]).line("y stbd [mm]", t, perr[1]).line("z down [mm]", t, perr[2]);
  p3.line("yaw [deg]", t, perr[3]);
  auto& p3b =
      plot.add_panel("The water's push on the vehicle (body): the servo's estimate vs truth",
                     "time [s]", "force [N]");
  p3b.line("estimate x fwd", t, push_est[0]).line("truth x fwd (at rest)", t, push_truth[0]);
  p3b.line("estimate y stbd", t, push_est[1]).line("truth y stbd (at rest)", t, push_truth[1]);
  auto& p4 = plot.add_panel("RM-GA fitness of the best individual", "time [s]", "fitness");
  p4.line("fitness", t, fitness).hline(0.6, "recognised (0.6)").y_limits(0.0, 1.0);
  auto& p5 = plot.add_panel("Thruster commands", "time [s]", "fraction of full thrust");
  for (int i = 0; i < n_thr; ++i) p5.line("T" + std::to_string(i + 1), t, thr[i]);
  p5.y_limits(-1.0, 1.0);
  auto& p6 = plot.add_panel("Mission state", "time [s]", "", 260);
  p6.step("state", t, state);
  std::vector<std::pair<double, std::string>> cats;
  for (int s = 0; s < control::kMissionStateCount; ++s) {
    cats.emplace_back(s, control::to_string(static_cast<control::MissionState>(s)));
  }
  p6.y_categories(cats);
  if (trial.recharge && !trial.charge.samples.empty()) {
    std::vector<double> ct, soc, amps, watts, speed, seated;
    for (const ChargeSample& c : trial.charge.samples) {
      ct.push_back(c.time_s);
      soc.push_back(100.0 * c.soc_fraction);
      amps.push_back(c.charge_current_a);
      watts.push_back(c.thruster_power_w);
      speed.push_back(100.0 * c.current_speed_mps);
      seated.push_back(c.seated ? 1.0 : 0.0);
    }
    auto& p7 = plot.add_panel("Battery and charger (battery time runs faster while seated)",
                              "time [s]", "[%] / [A]");
    p7.line("state of charge [%]", ct, soc).line("charge current [A]", ct, amps);
    auto& p8 =
        plot.add_panel("The hold: thruster power, water current, seat", "time [s]", "[W] / [cm/s]");
    p8.line("thruster power [W]", ct, watts).line("current speed [cm/s]", ct, speed);
    auto& p9 = plot.add_panel("Probe seated (truth)", "time [s]", "", 200);
    p9.step("seated", ct, seated).y_categories({{0.0, "out"}, {1.0, "seated"}});
  }
  plot.save_png(png_path);
}

void write_sim_outputs(const std::string& dir, const std::vector<TrialResult>& results,
                       const SimSummary& summary, int plot_trials) {
  std::filesystem::create_directories(dir);
  std::ostringstream table;
  table << "trial,seed,start_distance_m,bearing_deg,heading_offset_deg,current_mps,noise_sigma,"
           "success,captured,final_state,aborts,failsafe,time_to_dock_s,lateral_error_mm,yaw_error_"
           "deg,"
           "sim_time_s,ticks,overruns,jitter_p99_ms,estimator_ms_mean,recognised_fraction,"
           "estimate_error_mm_median,ok_ticks,ok_wrong_ticks,ok_error_mm_max,ok_error_deg_max,"
           "ok_over_bound_ticks,ok_carried_ticks,frame_cpu_ms_p95";
  const bool recharge = summary.recharge;
  if (recharge) {
    table << ",recharged,charged,departed,end_of_charge,seated_h,contact_fraction,"
             "unseated_unnoticed_max_s,reseats,hold_wh,charged_wh,hold_fraction,soc_start,soc_end,"
             "undock_clearance_m,undock_marker_in_view";
  }
  table << '\n';
  for (const TrialResult& r : results) {
    const auto& c = r.conditions;
    table << c.index << ',' << c.seed << ',' << c.distance_m << ',' << c.bearing_deg << ','
          << c.heading_offset_deg << ',' << c.current_mean_world_mps.norm() << ','
          << c.image_noise_sigma << ',' << trial_docked(r) << ',' << r.docked << ','
          << r.final_state << ',' << r.aborts << ',' << r.failsafe << ',' << r.time_to_dock_s << ','
          << r.lateral_error_mm << ',' << r.yaw_error_deg << ',' << r.sim_time_s << ',' << r.ticks
          << ',' << r.overruns << ',' << r.jitter_p99_ms << ',' << r.estimator_ms_mean << ','
          << r.recognised_fraction << ',' << r.estimate_error_mm_median << ',' << r.ok_ticks << ','
          << r.ok_wrong_ticks << ',' << r.ok_error_mm_max << ',' << r.ok_error_deg_max << ','
          << r.ok_over_bound_ticks << ',' << r.ok_carried_ticks << ',' << r.frame_cpu_ms_p95;
    if (recharge) {
      const RechargeResult& h = r.charge;
      table << ',' << trial_recharged(r) << ',' << h.charged << ',' << h.departed << ",\""
            << h.end_reason << "\"," << h.seated_s / 3600.0 << ',' << h.contact_fraction << ','
            << h.unseated_unnoticed_max_s << ',' << h.reseats << ',' << h.hold_wh << ','
            << h.charged_wh << ',' << h.hold_fraction << ',' << h.soc_start << ',' << h.soc_end
            << ',' << h.undock_clearance_m << ',' << h.undock_marker_in_view;
    }
    table << '\n';
  }
  write_file_atomically(dir + "/trials.csv", table.str());
  write_file_atomically(dir + "/summary.json", summary_json(summary) + "\n");
  char name[64];
  for (const TrialResult& r : results) {
    if (r.records.empty()) continue;
    std::string csv = telemetry_csv_header();
    csv += '\n';
    char row[4096];
    for (const TelemetryRecord& rec : r.records) {
      csv.append(row, format_telemetry_csv_row(rec, row, sizeof(row)));
      csv += '\n';
    }
    std::snprintf(name, sizeof(name), "/trial_%03d.csv", r.conditions.index);
    write_file_atomically(dir + name, csv);
    // The first few, and every trial that did not dock within tolerance: those are the ones a
    // person needs to look at.
    if (r.conditions.index < plot_trials || !trial_docked(r) ||
        (r.recharge && !trial_recharged(r))) {
      std::snprintf(name, sizeof(name), "/trial_%03d.png", r.conditions.index);
      plot_trial(r, dir + name);
    }
  }
}

}  // namespace rovctl::app
