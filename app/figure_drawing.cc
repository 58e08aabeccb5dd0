#include "app/figure_drawing.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "common/error.h"

extern char** environ;

namespace granasym {
namespace {
namespace fs = std::filesystem;

std::string FindOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = dirs.substr(start, end - start);
    if (!dir.empty()) {
      const std::string candidate = dir + "/" + program;
      if (access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    start = end + 1;
  }
  return "";
}

// Runs argv, returns its exit status and its stdout and stderr together.
int RunCapturing(const std::vector<std::string>& argv, std::string* output) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) throw RuntimeError("pipe() failed for " + argv[0]);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_fds[1]);
  if (spawned != 0) {
    close(pipe_fds[0]);
    throw RuntimeError("cannot start " + argv[0]);
  }
  char buffer[4096];
  ssize_t n = 0;
  while ((n = read(pipe_fds[0], buffer, sizeof buffer)) > 0) output->append(buffer, n);
  close(pipe_fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

// Draws one figure from its wrapper in every format; returns "" or why it failed.
std::string Draw(const std::string& gnuplot, const std::string& wrapper,
                 const std::string& output_stem) {
  for (const char* term : {"png", "pdf", "svg"}) {
    const std::string file = output_stem + "." + term;
    fs::remove(file);
    std::string output;
    const int status =
        RunCapturing({gnuplot, "-e", std::string("term='") + term + "'", wrapper}, &output);
    while (!output.empty() && (output.back() == '\n' || output.back() == ' ')) output.pop_back();
    if (status != 0) return "gnuplot failed (exit " + std::to_string(status) + "): " + output;
    if (!output.empty()) return "gnuplot printed: " + output;
    if (!fs::exists(file) || fs::file_size(file) == 0) return "gnuplot wrote no " + file;
  }
  return "";
}

}  // namespace

std::string PlotsDirectory() {
  if (const char* dir = std::getenv("GRANASYM_PLOTS_DIR")) return dir;
  return GRANASYM_PLOTS_DIR;
}

std::string DrawCalibrationPaths(const std::string& plot_data_dir) {
  if (!fs::exists(plot_data_dir + "/paths.txt")) return "";
  const std::string gnuplot = FindOnPath("gnuplot");
  if (gnuplot.empty()) return "gnuplot is not on PATH (Debian: apt-get install gnuplot-nox)";
  // plots/calibration_paths.gp beside plots/study/.
  fs::path study_plots = fs::path(PlotsDirectory()).lexically_normal();
  if (!study_plots.has_filename()) study_plots = study_plots.parent_path();
  const std::string chosen = (study_plots.parent_path() / "calibration_paths.gp").string();
  if (!fs::exists(chosen)) return "no " + chosen;
  const std::string png = plot_data_dir + "/paths.png";
  fs::remove(png);
  std::string output;
  const int status = RunCapturing({gnuplot, "-e", "dir='" + plot_data_dir + "'", chosen}, &output);
  if (status != 0) return "gnuplot failed (exit " + std::to_string(status) + "): " + output;
  if (!fs::exists(png) || fs::file_size(png) == 0) return "gnuplot wrote no " + png;
  return "";
}

int DrawFigures(const std::string& out, std::vector<analysis::FigureSpec>* figures,
                bool data_only) {
  const auto wrappers = analysis::WriteFigureScripts(out, PlotsDirectory(), *figures);
  const std::string gnuplot = data_only ? "" : FindOnPath("gnuplot");
  int failed = 0;
  for (analysis::FigureSpec& figure : *figures) {
    if (!figure.not_drawn.empty()) {
      std::printf("  %-28s not drawn: %s\n", figure.stem.c_str(), figure.not_drawn.c_str());
      continue;
    }
    const auto wrapper = std::find_if(wrappers.begin(), wrappers.end(), [&](const auto& entry) {
      return entry.first == figure.stem;
    });
    if (data_only || wrapper == wrappers.end()) continue;
    const std::string stem = out + "/figures/" + figure.stem;
    const std::string why = gnuplot.empty() ? "gnuplot is not on PATH (Debian: apt-get install "
                                              "gnuplot-nox)"
                                            : Draw(gnuplot, wrapper->second, stem);
    if (why.empty()) {
      std::printf("  %-28s %s.png, .pdf, .svg\n", figure.stem.c_str(), stem.c_str());
    } else {
      ++failed;
      figure.not_drawn = why;
      figure.caption += " Not drawn: " + why;
      std::printf("  %-28s FAILED: %s\n", figure.stem.c_str(), why.c_str());
    }
  }
  return failed;
}

}  // namespace granasym
