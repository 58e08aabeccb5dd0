// `granasym study figures DIR [--only STEM]...`: writes the figure data
// (analysis/figure_data.h) under DIR/figures/data/, draws every figure with
// the gnuplot scripts of plots/study/ into DIR/figures/<stem>.png and .pdf,
// and writes DIR/figures/index.tsv (a figure that could not be drawn has
// the reason in its caption). gnuplot is found on PATH; the scripts next to
// the sources (GRANASYM_PLOTS_DIR at build time), or where the environment
// variable GRANASYM_PLOTS_DIR points.
#include "app/study_figures_command.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/figure_data.h"
#include "common/error.h"
#include "common/stopwatch.h"

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

std::string PlotsDirectory() {
  if (const char* dir = std::getenv("GRANASYM_PLOTS_DIR")) return dir;
  return GRANASYM_PLOTS_DIR;
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

// Draws one figure in both formats; returns "" or why it failed.
std::string Draw(const std::string& gnuplot, const std::string& scripts,
                 const std::string& directory, const analysis::FigureSpec& figure) {
  const std::string script = scripts + "/" + figure.script;
  if (!fs::exists(script)) return "the script " + script + " does not exist";
  for (const char* term : {"png", "pdf"}) {
    const std::string file = directory + "/figures/" + figure.stem + "." + term;
    fs::remove(file);
    std::string assignments = "data='" + directory + "/figures/data'; out='" + directory +
                              "/figures/" + figure.stem + "'; term='" + term + "'; scripts='" +
                              scripts + "'";
    for (const auto& [name, value] : figure.variables) assignments += "; " + name + "=" + value;
    std::string output;
    const int status = RunCapturing({gnuplot, "-e", assignments, script}, &output);
    while (!output.empty() && (output.back() == '\n' || output.back() == ' ')) output.pop_back();
    if (status != 0) return "gnuplot failed (exit " + std::to_string(status) + "): " + output;
    if (!output.empty()) return "gnuplot printed: " + output;
    if (!fs::exists(file) || fs::file_size(file) == 0) return "gnuplot wrote no " + file;
  }
  return "";
}

struct FiguresFlags {
  std::string directory;
  std::vector<std::string> only;
  bool data_only = false;
};

void RunFigures(const FiguresFlags& flags) {
  const Stopwatch clock;
  for (const std::string& path : {flags.directory, PlotsDirectory()}) {
    if (path.find('\'') != std::string::npos) {
      throw InputError("'" + path + "': a folder name with a quote cannot be passed to gnuplot");
    }
  }
  std::vector<analysis::FigureSpec> figures = analysis::WriteFigureData(flags.directory);
  const std::string gnuplot = flags.data_only ? "" : FindOnPath("gnuplot");
  int drawn = 0, failed = 0;
  for (analysis::FigureSpec& figure : figures) {
    if (!flags.only.empty() &&
        std::find(flags.only.begin(), flags.only.end(), figure.stem) == flags.only.end()) {
      continue;
    }
    if (!figure.not_drawn.empty()) {
      std::printf("  %-28s not drawn: %s\n", figure.stem.c_str(), figure.not_drawn.c_str());
      continue;
    }
    if (flags.data_only) continue;
    std::string why = gnuplot.empty() ? "gnuplot is not on PATH (Debian: apt-get install "
                                        "gnuplot-nox)"
                                      : Draw(gnuplot, PlotsDirectory(), flags.directory, figure);
    if (why.empty()) {
      ++drawn;
      std::printf("  %-28s %s/figures/%s.png, .pdf\n", figure.stem.c_str(), flags.directory.c_str(),
                  figure.stem.c_str());
    } else {
      ++failed;
      figure.not_drawn = why;
      figure.caption += " Not drawn: " + why;
      std::printf("  %-28s FAILED: %s\n", figure.stem.c_str(), why.c_str());
    }
  }
  analysis::WriteFigureIndex(flags.directory, figures);
  std::printf("%d figures drawn, %d failed, in %.1f s; index: %s/figures/index.tsv\n", drawn,
              failed, clock.Seconds(), flags.directory.c_str());
  if (failed > 0) throw CLI::RuntimeError(4);
}

}  // namespace

void RegisterStudyFiguresCommand(CLI::App* study) {
  static FiguresFlags flags;
  CLI::App* figures = study->add_subcommand(
      "figures",
      "the paper's figures from a study folder: DIR/figures/<stem>.png and .pdf, their data "
      "under DIR/figures/data/, captions in DIR/figures/index.tsv");
  figures->add_option("dir", flags.directory, "study folder")
      ->required()
      ->check(CLI::ExistingDirectory);
  figures->add_option("--only", flags.only, "draw only these stems (e.g. fig16_asymptotic_states)");
  figures->add_flag("--data-only", flags.data_only, "write the data and the index, draw nothing");
  figures->callback([] { RunFigures(flags); });
}

}  // namespace granasym
