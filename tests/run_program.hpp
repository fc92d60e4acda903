#pragma once

// The mpile program run by a test in a child process, for what only a process shows: its exit
// status, its command line, a limit on what it may write.
#include "tests/case_run.hpp"

#include <csignal>
#include <filesystem>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace mpile {

struct Finished {
  bool exited = false;
  int status = -1; // the exit status, or the signal that ended it
  std::string err;
};

/// Runs the mpile program with `arguments`, each file it writes limited to `file_bytes` (0: no
/// limit), its standard error kept.
inline Finished run_mpile(const std::vector<std::string>& arguments, rlim_t file_bytes,
                          const std::filesystem::path& err_file) {
  std::vector<std::string> words{MPILE_BINARY};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& word : words) {
    argv.push_back(word.data());
  }
  argv.push_back(nullptr);
  const pid_t child = fork();
  if (child == 0) {
    if (file_bytes > 0) {
      const rlimit limit{file_bytes, file_bytes};
      setrlimit(RLIMIT_FSIZE, &limit);
      // SIGXFSZ at its default (it kills): mpile must ignore it itself, as under a user's ulimit.
      std::signal(SIGXFSZ, SIG_DFL);
    }
    const int err = open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = open("/dev/null", O_WRONLY);
    dup2(err, STDERR_FILENO);
    dup2(null, STDOUT_FILENO);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(child, &status, 0);
  Finished finished;
  finished.exited = WIFEXITED(status);
  finished.status = finished.exited ? WEXITSTATUS(status) : WTERMSIG(status);
  finished.err = read_text(err_file);
  return finished;
}

} // namespace mpile
