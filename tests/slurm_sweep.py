#!/usr/bin/python3
"""`mpile sweep --profile` on a real Slurm cluster: a single-node cluster started here, as the
current user, everything it needs (slurm.conf, munge key and socket, state, spool, logs) in a
temporary directory of its own, and stopped with all its processes whatever happens.

The sweep is tests/data/sweeps/spring_slurm.toml (2 x 2 variants of the single material point, a
second or so each). Snakemake submits each variant as a Slurm job (its `--slurm` executor, from a
profile); variant v02's output directory is held by another process (the output lock), so its job
fails and `mpile sweep` reports it, gathers the other three and exits 1. With the lock released the
same command reruns v02 alone, as one more Slurm job, and gathers all four.

Checked: the jobs ran through Slurm (one job per variant, on the cluster's node, v02's first job
FAILED and its second COMPLETED, no other job); the table holds each variant's own values (kinetic
energy at t = 0 is 0.5 m v0^2); the finished variants were not run again; no process of the
cluster is left.

  slurm_sweep.py MPILE SWEEP_FILE WORK_DIRECTORY

Exits 77 (skipped, with the reason) where Slurm, munge or Snakemake is not installed, unless
MPILE_REQUIRE_SLURM=1 is set (the continuous integration sets it): then a skip is a failure.
"""
import fcntl
import getpass
import math
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

SKIPPED = 77
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "python"))

mpile_binary, sweep_file, work = sys.argv[1:4]


def skip(reason):
    if os.environ.get("MPILE_REQUIRE_SLURM") == "1":
        print(f"FAILED: the Slurm sweep test cannot run ({reason}) and MPILE_REQUIRE_SLURM=1")
        sys.exit(1)
    print(f"skipped: {reason}")
    sys.exit(SKIPPED)


programs = {}
for name in ["munged", "slurmctld", "slurmd", "sbatch", "srun", "scontrol", "sinfo", "scancel", "snakemake"]:
    path = shutil.which(name, path=os.environ.get("PATH", "") + ":/usr/sbin:/sbin")
    if path is None:
        skip(f"{name} is not installed (Debian: apt-get install slurm-wlm munge snakemake, "
             "or bash tools/setup.sh)")
    programs[name] = path
try:
    import mpile  # noqa: E402
except ImportError as e:
    skip(f"the mpile Python package cannot be imported: {e}")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def parent(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return int(f.read().rsplit(")", 1)[1].split()[1])
    except (OSError, IndexError, ValueError):
        return None


class Cluster:
    """slurmctld, slurmd and munged as children of this process, in a directory of their own."""

    def __init__(self):
        # Short paths: a Unix socket's path has at most 107 characters.
        self.root = tempfile.mkdtemp(prefix="mpile-slurm-")
        self.daemons = {}
        self.user = getpass.getuser()
        self.node = socket.gethostname().split(".")[0]
        self.conf = os.path.join(self.root, "slurm.conf")
        # Snakemake 7's Slurm executor reads USER (a login shell sets it; ctest may not).
        self.env = dict(os.environ, SLURM_CONF=self.conf, USER=self.user)
        for name in ["SLURM_JOB_ID", "SLURM_JOBID", "SLURM_CLUSTER_NAME"]:
            self.env.pop(name, None)

    def path(self, *parts):
        return os.path.join(self.root, *parts)

    def start(self):
        for d in ["munge", "state", "spool", "log"]:
            os.makedirs(self.path(d), mode=0o700)
        key = self.path("munge", "munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o400)
        socket_path = self.path("munge", "munge.socket")
        self.launch("munged", [programs["munged"], "--foreground", "--force",
                               f"--socket={socket_path}", f"--key-file={key}",
                               f"--log-file={self.path('log', 'munged.log')}",
                               f"--pid-file={self.path('munge', 'munged.pid')}",
                               f"--seed-file={self.path('munge', 'munged.seed')}"])
        self.wait_for(lambda: os.path.exists(socket_path), "munged's socket", 10)
        cpus = os.cpu_count() or 1
        with open(self.conf, "w") as f:
            f.write(f"""ClusterName=mpiletest
SlurmctldHost={self.node}(127.0.0.1)
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
SlurmUser={self.user}
SlurmdUser={self.user}
AuthType=auth/munge
AuthInfo=socket={socket_path}
CredType=cred/munge
StateSaveLocation={self.path('state')}
SlurmdSpoolDir={self.path('spool')}
SlurmctldPidFile={self.path('state', 'slurmctld.pid')}
SlurmdPidFile={self.path('spool', 'slurmd.pid')}
SlurmctldLogFile={self.path('log', 'slurmctld.log')}
SlurmdLogFile={self.path('log', 'slurmd.log')}
SlurmdParameters=config_overrides
PlugStackConfig={self.path('plugstack.conf')}
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
ReturnToService=2
MinJobAge=3600
KillWait=5
InactiveLimit=0
NodeName={self.node} NodeAddr=127.0.0.1 CPUs={cpus} RealMemory=1000 State=UNKNOWN
PartitionName=debug Nodes={self.node} Default=YES MaxTime=INFINITE State=UP
""")
        open(self.path("plugstack.conf"), "w").close()
        self.launch("slurmctld", [programs["slurmctld"], "-D", "-i", "-f", self.conf])
        self.launch("slurmd", [programs["slurmd"], "-D", "-N", self.node, "-f", self.conf])

        def node_idle():
            state = self.run(["sinfo", "--noheader", "-o", "%t"], check=False).stdout.strip()
            return state in ("idle", "mix", "alloc")
        self.wait_for(node_idle, "the node to register with slurmctld", 30)

    def launch(self, name, command):
        log = open(self.path("log", name + ".out"), "w")
        self.daemons[name] = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT,
                                              env=self.env, cwd=self.root, start_new_session=True)
        log.close()

    def wait_for(self, condition, what, seconds):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            for name, process in self.daemons.items():
                if process.poll() is not None:
                    raise RuntimeError(f"{name} exited with status {process.returncode} while "
                                       f"waiting for {what}:\n{self.logs()}")
            if condition():
                return
            time.sleep(0.2)
        raise RuntimeError(f"no {what} within {seconds} s:\n{self.logs()}")

    def run(self, command, check=True):
        return subprocess.run([programs.get(command[0], command[0])] + command[1:], env=self.env,
                              capture_output=True, text=True, check=check, timeout=60)

    def jobs(self):
        """(name, state, exit code, node list) of every job slurmctld knows."""
        out = self.run(["scontrol", "show", "jobs", "-o"], check=False).stdout
        jobs = []
        for line in out.splitlines():
            fields = dict(f.split("=", 1) for f in line.split() if "=" in f)
            if "JobId" in fields:
                jobs.append((int(fields["JobId"]), fields.get("JobName", ""), fields.get("JobState", ""),
                             fields.get("ExitCode", ""), fields.get("NodeList", "")))
        return sorted(jobs)

    def logs(self):
        text = ""
        for name in sorted(os.listdir(self.path("log"))):
            with open(self.path("log", name), errors="replace") as f:
                tail = f.read().splitlines()[-15:]
            text += f"--- {name}:\n" + "\n".join(tail) + "\n"
        return text

    def processes(self):
        """Processes still running that belong to the cluster: the daemons, and any other (a job
        step's slurmstepd, a job's shell) whose environment or command line names its directory."""
        found = {}
        for pid in os.listdir("/proc"):
            if not pid.isdigit() or int(pid) == os.getpid():
                continue
            try:
                with open(f"/proc/{pid}/environ", "rb") as f:
                    environ = f.read()
                with open(f"/proc/{pid}/cmdline", "rb") as f:
                    cmdline = f.read()
            except OSError:
                continue
            if self.root.encode() in environ or self.root.encode() in cmdline:
                found[int(pid)] = cmdline.replace(b"\0", b" ").decode(errors="replace").strip()
        return found

    def stop(self):
        """Cancels every job, stops the daemons (SIGTERM, then SIGKILL after 10 s) and ends any
        process left that names the cluster's directory; returns those that had to be killed."""
        if "slurmctld" in self.daemons and self.daemons["slurmctld"].poll() is None:
            self.run(["scancel", "--full", "--user", self.user], check=False)
            deadline = time.monotonic() + 15
            while time.monotonic() < deadline:
                if not any(state in ("RUNNING", "PENDING", "COMPLETING", "CONFIGURING")
                           for _, _, state, _, _ in self.jobs()):
                    break
                time.sleep(0.2)
        # A job's slurmstepd and shell end a moment after slurmctld counts the job done; the
        # daemons' own children (slurmctld's slurmscriptd) end with them.
        daemons = {process.pid for process in self.daemons.values()}

        def jobs_processes():
            return [pid for pid in self.processes() if pid not in daemons and parent(pid) not in daemons]
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and jobs_processes():
            time.sleep(0.2)
        for name in ["slurmd", "slurmctld", "munged"]:
            process = self.daemons.get(name)
            if process is not None and process.poll() is None:
                process.terminate()
                try:
                    process.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    process.kill()
                    process.wait()
        left = {}
        for _ in range(50):
            left = self.processes()
            if not left:
                break
            time.sleep(0.2)
        for pid in left:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        return left


def sweep(cluster, profile, out):
    """`mpile sweep --profile`; stopped with SIGTERM (which it passes on to Snakemake, which
    cancels its jobs) if this test is stopped or it runs past 180 s."""
    process = subprocess.Popen([mpile_binary, "sweep", sweep_file, "--out", out, "--profile", profile],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=cluster.env)
    try:
        stdout, stderr = process.communicate(timeout=180)
    except BaseException:
        process.terminate()
        try:
            process.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            process.kill()
            process.communicate()
        raise
    return subprocess.CompletedProcess(process.args, process.returncode, stdout, stderr)


failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
out = os.path.join(work, "sweep")
profile = os.path.join(work, "profile")
os.makedirs(profile)
# The profile of docs/sweeps.md, "On a cluster", for this cluster: its default partition (no
# account), a small memory request (the node offers 1000 MB), the jobs' states asked every second
# (Snakemake 7 takes a rate above 1 per second for every 33 s, its default on a cluster).
with open(os.path.join(profile, "config.yaml"), "w") as f:
    f.write("slurm: true\njobs: 4\nlatency-wait: 10\nmax-status-checks-per-second: 1\n"
            "default-resources:\n  - runtime=5\nset-resources:\n  - run:mem_mb=100\n")



class Stopped(Exception):
    pass


def stopped(signum, frame):
    raise Stopped(f"stopped by signal {signum}")


# A timeout's or a user's signal still stops the cluster (the finally below).
for signum in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
    signal.signal(signum, stopped)

started = time.monotonic()
cluster = Cluster()
left = {}
first = second = None
try:
    try:
        cluster.start()
    except (RuntimeError, OSError, subprocess.SubprocessError) as e:
        raise SystemExit(f"FAILED: the cluster did not start: {e}")
    print(f"cluster up in {time.monotonic() - started:.1f} s: node {cluster.node}, {cluster.root}")

    # Another process holds v02's output lock, as a run left writing there would: its job fails.
    held = os.path.join(out, "variants", "v02")
    os.makedirs(held)
    lock = open(os.path.join(held, ".mpile.lock"), "w")
    fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
    first = sweep(cluster, profile, out)
    after_first = cluster.jobs()
    lock.close()
    print(f"first sweep: exit status {first.returncode}, {time.monotonic() - started:.1f} s")
    check(first.returncode == 1, f"first sweep: exit status {first.returncode}, expected 1")
    check("1 of 4 variants did not finish" in first.stderr, "first sweep: the failure is not reported")
    check("v02 failed: --set phases.0.duration=1.0" in first.stderr, "first sweep: v02 is not named")
    check("another run is writing to" in first.stderr, "first sweep: the end of v02's log is not shown")
    check(len(after_first) == 4, f"first sweep: {len(after_first)} Slurm jobs, expected 4: {after_first}")
    check(all(node == cluster.node for *_, node in after_first), f"jobs not on the node: {after_first}")
    states = sorted(state for _, _, state, _, _ in after_first)
    check(states == ["COMPLETED", "COMPLETED", "COMPLETED", "FAILED"], f"first sweep: job states {states}")
    frame = mpile.open_sweep(out, form="pandas").set_index("variant")
    check([s.split(":")[0] for s in frame["status"]] == ["finished", "failed", "finished", "finished"],
          f"first sweep: statuses {list(frame['status'])}")

    histories = {v: os.path.join(out, "variants", v, "history.h5") for v in ["v01", "v03", "v04"]}
    before = {v: os.stat(h).st_mtime_ns for v, h in histories.items()}
    second = sweep(cluster, profile, out)
    after_second = cluster.jobs()
    print(f"second sweep: exit status {second.returncode}, {time.monotonic() - started:.1f} s")
    check(second.returncode == 0, f"second sweep: exit status {second.returncode}, expected 0")
    new = after_second[len(after_first):]
    check(len(new) == 1 and new[0][2] == "COMPLETED",
          f"second sweep: Slurm jobs {new}, expected one, COMPLETED")
    check(all(os.stat(h).st_mtime_ns == before[v] for v, h in histories.items()),
          "second sweep: a finished variant ran again")
    logs = os.path.join(out, ".snakemake", "slurm_logs", "rule_run")
    job_logs = sorted(os.listdir(logs)) if os.path.isdir(logs) else []
    check(job_logs == sorted(f"{job[0]}.log" for job in after_second),
          f"Slurm job logs {job_logs}, expected one per job")

    frame = mpile.open_sweep(out, form="pandas").set_index("variant")
    check(list(frame["status"]) == ["finished"] * 4, f"second sweep: statuses {list(frame['status'])}")
    for variant, row in frame.iterrows():
        v0 = float(row["bodies.0.velocity"].strip("[]").split(",")[0])
        check(math.isclose(row["kinetic_start"], 0.5 * v0 * v0, rel_tol=1e-12),
              f"{variant}: kinetic energy at t = 0 {row['kinetic_start']}, expected {0.5 * v0 * v0}")
    with open(os.path.join(out, "results.csv")) as f:
        check(len(f.read().strip().splitlines()) == 5, "results.csv does not hold a header and 4 rows")
except BaseException as e:
    failures.append(f"{type(e).__name__}: {e}")
finally:
    logs = cluster.logs() if os.path.isdir(cluster.path("log")) else ""
    left = cluster.stop()
    shutil.rmtree(cluster.root, ignore_errors=True)
check(not left, f"processes of the cluster left running, killed: {left}")

if failures:
    for name, result in [("first", first), ("second", second)]:
        if result is not None:
            print(f"{name} sweep:\n{result.stdout}{result.stderr[-3000:]}")
    print(logs)
    print("FAILED:\n  " + "\n  ".join(failures))
    sys.exit(1)
print(f"slurm sweep: 4 variants in 5 Slurm jobs, v02 failed and rerun alone, all gathered, "
      f"the cluster stopped ({time.monotonic() - started:.0f} s)")
