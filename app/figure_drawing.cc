#include "app/figure_drawing.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <tuple>

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

std::vector<std::string> DrawCalibrationFigures(const std::string& plot_data) {
  std::vector<std::string> lines;
  const std::string scripts = fs::path(PlotsDirectory()).parent_path().string();
  const std::string gnuplot = FindOnPath("gnuplot");
  for (const auto& [data, script, image] :
       {std::tuple<const char*, const char*, const char*>{"profiles.csv", "calibration_profiles.gp",
                                                          "profiles.png"},
        {"pareto.csv", "calibration_pareto.gp", "pareto.png"},
        {"paths.txt", "calibration_paths.gp", "paths.png"}}) {
    if (!fs::exists(fs::path(plot_data) / data)) continue;
    const std::string png = (fs::path(plot_data) / image).string();
    fs::remove(png);
    std::string why;
    if (gnuplot.empty()) {
      why = "gnuplot is not on PATH (Debian: apt-get install gnuplot-nox)";
    } else if (plot_data.find('\'') != std::string::npos) {
      why = "the folder's name holds a quote, which gnuplot's -e cannot take";
    } else {
      std::string output;
      const int status =
          RunCapturing({gnuplot, "-e", "dir='" + plot_data + "'", scripts + "/" + script}, &output);
      while (!output.empty() && (output.back() == '\n' || output.back() == ' ')) output.pop_back();
      if (status != 0) {
        why = "gnuplot failed (exit " + std::to_string(status) + "): " + output;
      } else if (!fs::exists(png) || fs::file_size(png) == 0) {
        why = "gnuplot wrote no " + png + (output.empty() ? "" : ": " + output);
      }
    }
    lines.push_back(why.empty() ? png : png + " not drawn: " + why);
  }
  return lines;
}

int DrawFigures(const std::string& out, std::vector<analysis::FigureSpec>* figures,
                bool data_only) {
  const auto wrappers = analysis::WriteFigureScripts(out, PlotsDirectory(), *figures);
  const std::string gnuplot = data_only ? "" : FindOnPath("gnuplot");
  int failed = 0;
  for (analysis::FigureSpec& figure : *figures) {
    // The images of an earlier run go first: a figure not drawn this time
    // (no gnuplot, no data, a failure, --data-only) shows none.
    for (const char* extension : {".png", ".pdf", ".svg"}) {
      fs::remove(out + "/figures/" + figure.stem + extension);
    }
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
