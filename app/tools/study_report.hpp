// What `rovctl study` writes: a CSV of every run, a markdown report with our Table 1 / Table 2 /
// Fig. 8 beside the paper's, PNG plots of Fig. 8 and Fig. 9, and the --json summary.
#pragma once

#include <string>

#include "app/tools/study.hpp"

namespace rovctl::app {

struct StudyFiles {
  std::string csv;       // study_runs.csv: one row per run
  std::string report;    // study_report.md
  std::string fig8_png;  // fig8_generations.png
  std::string fig9_png;  // fig9_convergence.png: time to the goal fitness
  std::string pose_png;  // fig9_pose.png: time to the goal accuracy
};

std::string study_runs_csv(const StudyResult& result);
// `command_line` is quoted in the report so that it can be rerun.
std::string study_report_markdown(const StudyResult& result, const std::string& command_line);
void plot_study_fig8(const StudyResult& result, const std::string& png_path);
// pose = false: time to the goal fitness (the paper's Fig. 9); true: to the goal accuracy.
void plot_study_fig9(const StudyResult& result, bool pose, const std::string& png_path);

// All of the above into `dir` (which must exist), each written to a temporary name and renamed.
StudyFiles write_study_outputs(const std::string& dir, const StudyResult& result,
                               const std::string& command_line);

// One JSON object: fig8 (population -> generations per frame, faithful mode), table1 (faithful
// rows), best (per population and overall), and the same for every variant, plus the files.
std::string study_json(const StudyResult& result, const StudyFiles& files);
// A few lines for the terminal: Table 1 per variant and where the files are.
std::string study_text(const StudyResult& result, const StudyFiles& files);

}  // namespace rovctl::app
