#include "app/sweep_command.hpp"

#include "app/run_command.hpp"
#include "cases/case_error.hpp"
#include "cases/case_warnings.hpp"
#include "cases/sweep_file.hpp"
#include "io/replace_file.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <tbb/info.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

extern char** environ;

namespace mpile {

namespace {

namespace fs = std::filesystem;

/// A TOML basic string.
std::string quoted(const std::string& text) {
  return toml_text(TomlValue(text));
}

std::string quoted_list(const std::vector<std::string>& items) {
  std::string list = "[";
  for (std::size_t i = 0; i < items.size(); ++i) {
    list += (i > 0 ? ", " : "") + quoted(items[i]);
  }
  return list + "]";
}

/// The validated sweep as the workflow and the gathering read it (absolute paths, every variant).
std::string sweep_record(const SweepSpec& sweep, const std::string& case_path,
                         const std::string& mpile) {
  std::ostringstream s;
  s << "# The sweep " << sweep.file << " as `mpile sweep` expanded it; the workflow reads it.\n";
  s << "title = " << quoted(sweep.title) << "\n";
  s << "sweep_file = " << quoted(fs::absolute(sweep.file).lexically_normal().string()) << "\n";
  s << "case = " << quoted(case_path) << "\n";
  s << "mpile = " << quoted(mpile) << "\n";
  s << "python = " << quoted(MPILE_PYTHON_DIR) << "\n";
  s << "threads = " << sweep.threads << "\n";
  std::vector<std::string> keys;
  for (const SweepParameter& p : sweep.parameters) {
    keys.push_back(p.key);
  }
  s << "parameters = " << quoted_list(keys) << "\n";
  for (const GatherSpec& g : sweep.gather) {
    s << "\n[[gather]]\nname = " << quoted(g.name) << "\nseries = " << quoted(g.series) << "\n";
    if (g.at_penetration) {
      s << "body = " << quoted(g.body)
        << "\nat_penetration = " << toml_text(TomlValue(*g.at_penetration)) << "\n";
    }
    if (g.at_time) {
      s << "at_time = " << toml_text(TomlValue(*g.at_time)) << "\n";
    }
    if (!g.reduce.empty()) {
      s << "reduce = " << quoted(g.reduce) << "\n";
    }
    if (!g.phase.empty()) {
      s << "phase = " << quoted(g.phase) << "\n";
    }
  }
  for (const SweepVariant& v : sweep.variants) {
    s << "\n[[variants]]\nid = " << quoted(v.id) << "\nvalues = " << quoted_list(v.values)
      << "\nsets = " << quoted_list(v.sets) << "\n";
  }
  return s.str();
}

/// The Snakemake workflow: one job per variant (its output a marker written only when the run
/// succeeded, so a failed variant runs again next time and a finished one does not), then the
/// gathering. The run's --set values are the job's params: changing a variant's values reruns it.
std::string snakefile(const std::string& sweep_file) {
  std::ostringstream s;
  s << "# The workflow of the sweep " << sweep_file << ", written by `mpile sweep`.\n"
    << "# Run from this directory:\n"
    << "#   snakemake --cores 2 --keep-going --rerun-triggers mtime params input\n"
    << "# (a finished variant reruns for changed values, not for another mpile build); on a\n"
    << "# cluster, see docs/sweeps.md. Each variant's run is variants/<id>/: its outputs, its\n"
    << "# run.log, and output.log, what its last attempt printed. A variant stopped before its\n"
    << "# end (Ctrl-C, a time limit, a lost node) continues from its checkpoint (--continue).\n"
    << "import os\n"
    << "import shlex\n"
    << "import sys\n"
    << "import tomllib\n\n"
    << "with open(\"sweep.toml\", \"rb\") as f:\n"
    << "    SWEEP = tomllib.load(f)\n"
    << "VARIANTS = {v[\"id\"]: v for v in SWEEP[\"variants\"]}\n\n"
    << "# On a cluster, only the runs are submitted; the table is gathered where Snakemake runs.\n"
    << "localrules:\n"
    << "    all,\n"
    << "    gather,\n\n\n"
    << "wildcard_constraints:\n"
    << "    variant=\"v[0-9]+\",\n\n\n"
    << "def literal(path):\n"
    << "    # A path quoted for the shell, its braces kept from Snakemake's formatting.\n"
    << "    return shlex.quote(path).replace(\"{\", \"{{\").replace(\"}\", \"}}\")\n\n\n"
    << "def finished(wildcards):\n"
    << "    # With --config partial=1 the table gathers the variants that have finished so far.\n"
    << "    markers = [f\"variants/{v}/finished\" for v in VARIANTS]\n"
    << "    if config.get(\"partial\"):\n"
    << "        return [m for m in markers if os.path.exists(m)]\n"
    << "    return markers\n\n\n"
    << "rule all:\n"
    << "    input:\n"
    << "        \"gathered\",\n\n\n"
    << "rule run:\n"
    << "    output:\n"
    << "        touch(\"variants/{variant}/finished\"),\n"
    << "    log:\n"
    << "        \"variants/{variant}/output.log\",\n"
    << "    params:\n"
    << "        sets=lambda w: \" \".join(\"--set \" + shlex.quote(s) for s in "
       "VARIANTS[w.variant][\"sets\"]),\n"
    << "    threads: SWEEP[\"threads\"]\n"
    << "    resources:\n"
    << "        mem_mb=2000,\n"
    << "    shell:\n"
    << "        literal(SWEEP[\"mpile\"]) + \" run \" + literal(SWEEP[\"case\"]) + \" "
       "{params.sets} --out variants/{wildcards.variant} --continue --threads {threads} > {log} "
       "2>&1\"\n\n\n"
    << "rule gather:\n"
    << "    input:\n"
    << "        finished,\n"
    // Its output is a marker, not the tables: Snakemake deletes a job's outputs before it runs
    // (and after it fails), which lost the last complete results.csv and results.nc whenever a
    // gathering failed; mpile.sweep.gather replaces them itself, all or none.
    << "    output:\n"
    << "        touch(\"gathered\"),\n"
    << "    run:\n"
    << "        try:\n"
    << "            import mpile.sweep\n"
    << "        except ImportError:\n"
    << "            sys.path.insert(0, SWEEP[\"python\"])\n"
    << "            import mpile.sweep\n"
    << "        mpile.sweep.gather(\".\")\n";
  return s.str();
}

/// The process group of the program running, for the signal handler to pass signals on to.
volatile std::sig_atomic_t running_group = 0;
volatile std::sig_atomic_t interrupted = 0;

extern "C" void pass_on_signal(int signal) {
  interrupted = 1;
  if (running_group > 0) {
    ::kill(-running_group, signal);
  }
}

/// Runs a program found on PATH in a process group of its own and waits for it; returns its exit
/// status, 128 + signal when it was killed, minus errno when it could not start. SIGINT and
/// SIGTERM sent to this process (Ctrl-C, a batch system's stop) are passed on to the whole group:
/// Snakemake and the runs it started, which write their checkpoints and stop.
int run_program(const std::vector<std::string>& arguments) {
  std::vector<char*> argv;
  for (const std::string& a : arguments) {
    argv.push_back(const_cast<char*>(a.c_str()));
  }
  argv.push_back(nullptr);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setpgroup(&attributes, 0);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  struct sigaction pass_on {};
  pass_on.sa_handler = pass_on_signal;
  sigemptyset(&pass_on.sa_mask);
  struct sigaction previous_int {};
  struct sigaction previous_term {};
  sigaction(SIGINT, &pass_on, &previous_int);
  sigaction(SIGTERM, &pass_on, &previous_term);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], nullptr, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  int status = 0;
  if (spawned == 0) {
    running_group = pid;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    running_group = 0;
  }
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
  if (spawned != 0) {
    return -spawned;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// The last lines of a file.
std::string tail(const fs::path& file, std::size_t lines) {
  std::ifstream in(file);
  std::deque<std::string> last;
  for (std::string line; std::getline(in, line);) {
    last.push_back(line);
    if (last.size() > lines) {
      last.pop_front();
    }
  }
  std::string text;
  for (const std::string& line : last) {
    text += "      " + line + "\n";
  }
  return text;
}

/// Writes a whole file, replacing the old one in one step.
void write_file(const fs::path& path, const std::string& text) {
  const std::string temporary = path.string() + ".part";
  {
    std::ofstream file(temporary);
    file << text;
    if (!file.flush()) {
      throw std::runtime_error("cannot write " + temporary + ": " + std::strerror(errno));
    }
  }
  replace_file(temporary, path.string());
}

std::string executable_path() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? std::string("mpile") : self.string();
}

} // namespace

int sweep_command(const SweepOptions& options, std::ostream& out, std::ostream& err) {
  SweepSpec sweep;
  std::vector<CaseWarning> warnings;
  try {
    sweep = read_sweep_file(options.file);
    warnings = validate_sweep(sweep);
  } catch (const CaseError& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_bad_input;
  }
  // The variants' warnings before anything runs, as `mpile run` gives a case's.
  print_case_warnings(err, warnings, options.strict);
  if (options.strict && refused_when_strict(warnings)) {
    return exit_bad_input;
  }
  const fs::path directory = options.output_directory.empty()
                                 ? fs::path("out") / "sweeps" / fs::path(options.file).stem()
                                 : fs::path(options.output_directory);
  const std::string case_path =
      fs::absolute(fs::path(options.file).parent_path() / sweep.case_path).lexically_normal();
  // Snakemake holds a lock in .snakemake/locks while it runs a workflow in the directory, and
  // leaves it behind when killed. Seen before the workflow files are written, so that a running
  // sweep's Snakefile is not replaced under it and the user reads what to do, not Snakemake's
  // raw lock error after the workflow was rewritten.
  std::error_code lock_error;
  const fs::path locks = directory / ".snakemake" / "locks";
  if (fs::is_directory(locks, lock_error) && !fs::is_empty(locks, lock_error)) {
    err << "mpile: " << directory.string()
        << ": another sweep is running in this directory (Snakemake's lock in .snakemake/locks); "
           "wait for it to end, or, if none is running (a sweep that was killed), remove the lock "
           "with: snakemake --snakefile "
        << (directory / "Snakefile").string() << " --directory " << directory.string()
        << " --unlock\n";
    return exit_failure;
  }
  try {
    fs::create_directories(directory / "variants");
    write_file(directory / "sweep.toml", sweep_record(sweep, case_path, executable_path()));
    write_file(directory / "Snakefile", snakefile(sweep.file));
  } catch (const std::exception& e) {
    err << "mpile: " << directory.string() << ": cannot write the workflow: " << e.what() << '\n';
    return exit_failure;
  }
  const int cores = options.cores > 0 ? options.cores : tbb::info::default_concurrency();
  // Both Snakemake calls: the workflow, and what reruns a finished variant (changed values, not a
  // changed workflow text: another mpile build or its path).
  const std::vector<std::string> workflow{"snakemake",
                                          "--snakefile",
                                          (directory / "Snakefile").string(),
                                          "--directory",
                                          directory.string(),
                                          "--rerun-triggers",
                                          "mtime",
                                          "params",
                                          "input",
                                          "--quiet",
                                          "rules"};
  std::vector<std::string> snakemake = workflow;
  snakemake.push_back("--keep-going");
  if (options.profile.empty()) {
    snakemake.insert(snakemake.end(), {"--cores", std::to_string(cores)});
  } else {
    snakemake.insert(snakemake.end(), {"--profile", options.profile});
  }
  out << sweep.file << ": " << sweep.title << ": " << sweep.variants.size() << " variants of "
      << case_path << ", workflow in " << directory.string() << "\n";
  if (options.prepare) {
    out << "run it with:";
    for (const std::string& a : snakemake) {
      out << " " << a;
    }
    out << "\n";
    return exit_success;
  }

  const int status = run_program(snakemake);
  if (status < 0) {
    err << "mpile: cannot start snakemake (" << std::strerror(-status)
        << "); install it (Debian: apt-get install snakemake)\n";
    return exit_failure;
  }
  if (interrupted != 0 || status == 128 + SIGINT || status == 128 + SIGTERM) {
    err << "mpile: the sweep was interrupted; run the same command again to continue it\n";
    return exit_interrupted;
  }
  std::size_t failed = 0;
  std::ostringstream report;
  for (const SweepVariant& v : sweep.variants) {
    const fs::path run = directory / "variants" / v.id;
    if (fs::exists(run / "finished")) {
      continue;
    }
    ++failed;
    std::string values;
    for (const std::string& set : v.sets) {
      values += " --set " + set;
    }
    if (fs::exists(run / "output.log")) {
      report << "  " << v.id << " failed:" << values << "\n    " << (run / "output.log").string()
             << " ends:\n"
             << tail(run / "output.log", 4);
    } else {
      report << "  " << v.id << " did not run:" << values << "\n";
    }
  }
  if (failed > 0) {
    // The table of the variants that did finish, so that a study is not held up by one case.
    // Here, not through a profile: the gathering is a local job, and a cluster profile's settings
    // would only be in its way.
    std::vector<std::string> gather = workflow;
    gather.insert(gather.end(), {"--cores", "1", "--config", "partial=1", "--forcerun", "gather",
                                 "--", "gather"});
    run_program(gather);
    err << "mpile: " << failed << " of " << sweep.variants.size()
        << " variants did not finish (run the same command to retry them):\n"
        << report.str();
  }
  const fs::path table = directory / "results.csv";
  if (fs::exists(table)) {
    out << "results: " << table.string() << ", " << (directory / "results.nc").string() << "\n";
  }
  return failed == 0 && status == 0 ? exit_success : exit_failure;
}

} // namespace mpile
