"""One damaged run, every command that reads runs (issue 50): each opens a run through io::Run, so each refuses the
same damage the same way, naming the file, in under a second of CPU and 100 MB beyond the binary's own start. The
damage: the trajectory cut short, an event table edited (same size: only the hash tells), the contacts of another
recording copied in, the contacts padded to 20 GiB (sparse: no disk is used), the manifest edited. The Python
package's readers refuse the same runs (through the compiled module's checks when it is there)."""
import os
import shutil
import subprocess

import pytest

import siloscope

PAPER = os.path.join(os.path.dirname(__file__), "..", "..", "assets", "scenes", "paper.toml")


def _run(binary, out, seed):
    subprocess.run([binary, "run", PAPER, "--duration", "8", "--set", "settle_time=2", "--seed", str(seed),
                    "--trajectory-fps", "10", "--quiet", "--out", str(out)], check=True)


@pytest.fixture(scope="module")
def baseline_mb(binary, tmp_path_factory):
    """The binary's own peak memory when it does nothing (`--version`): the shared libraries it maps (Mesa's
    LLVM among them) before any command runs. A refusal may cost 100 MB beyond it at most."""
    log = tmp_path_factory.mktemp("baseline") / "log"
    return _measured([binary, "--version"], log)[3]


@pytest.fixture(scope="module")
def baseline_cpu(binary, tmp_path_factory):
    """The binary's own CPU seconds when it does nothing (`--version`, the fastest of three): its start-up, 0.28 s
    in a release build and 0.6 s under AddressSanitizer on the 2-core machine. A refusal may cost 1 s beyond it
    (an absolute second failed the sanitizer pass at 1.00-1.11 s: start-up, not reading)."""
    log = tmp_path_factory.mktemp("baseline_cpu") / "log"
    return min(_measured([binary, "--version"], log)[2] for _ in range(3))


@pytest.fixture(scope="module")
def made(binary, tmp_path_factory):
    d = tmp_path_factory.mktemp("damaged")
    _run(binary, d / "a", 1)
    _run(binary, d / "b", 2)
    return d


def _cut(run):
    p = run / "trajectory.sstraj"
    data = p.read_bytes()
    p.write_bytes(data[:len(data) - 7])
    return "trajectory.sstraj"


def _edited(run):
    p = run / "clogs.csv"
    data = bytearray(p.read_bytes())
    for i in range(len(data) - 2, 0, -1):
        if chr(data[i]).isdigit():
            data[i] = ord("1") if data[i] != ord("1") else ord("2")
            break
    p.write_bytes(bytes(data))
    return "clogs.csv"


def _foreign_contacts(run, other):
    shutil.copyfile(other / "contacts.sscon", run / "contacts.sscon")
    return "contacts.sscon"


def _oversized_contacts(run):
    with open(run / "contacts.sscon", "r+b") as f:
        f.truncate(20 << 30)
    return "contacts.sscon"


def _manifest_edited(run):
    m = run / "manifest.toml"
    text = m.read_text()
    at = text.index('["exits.csv", ') + len('["exits.csv", ')
    m.write_text(text[:at] + "1" + text[at:])
    return "manifest.toml"


DAMAGE = ["cut", "edited", "foreign contacts", "oversized contacts", "manifest edited"]

# Every command that reads a run, as a user would call it.
COMMANDS = {
    "inspect": lambda r, t: ["inspect", r, "--script", t + "/s.txt"],
    "frame": lambda r, t: ["frame", r, "--at", "t:1", "--size", "320x180", "--out", t + "/f.png"],
    "filmstrip": lambda r, t: ["filmstrip", r, "--clog", "1", "--out", t + "/fs.png"],
    "gallery": lambda r, t: ["gallery", r, "--out", t + "/g.png"],
    "timeline": lambda r, t: ["timeline", r, "--out", t + "/t.png"],
    "export csv": lambda r, t: ["export", r, "--format", "csv", "--out", t + "/x.csv"],
    "export vtu": lambda r, t: ["export", r, "--format", "vtu", "--out", t + "/vtu"],
    "analyze": lambda r, t: ["analyze", r, "--out", t + "/an"],
    "record --compare-run": lambda r, t: ["record", PAPER, "--duration", "1", "--size", "320x180", "--compare-run",
                                          r, "--out", t + "/cmp"],
}


def _damage(kind, run, other):
    return {"cut": lambda: _cut(run), "edited": lambda: _edited(run),
            "foreign contacts": lambda: _foreign_contacts(run, other),
            "oversized contacts": lambda: _oversized_contacts(run),
            "manifest edited": lambda: _manifest_edited(run)}[kind]()


def _measured(argv, log):
    """Runs argv, its stderr to `log`; returns (exit code, stderr, CPU seconds, peak resident MB) of that process
    alone (os.wait4 reports the one child it waited for)."""
    with open(log, "w") as err:
        p = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    return p.returncode, open(log).read(), usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024


@pytest.mark.parametrize("damage", DAMAGE)
@pytest.mark.parametrize("command", COMMANDS)
def test_every_run_reader_refuses_the_damaged_run_naming_the_file(made, baseline_mb, baseline_cpu, tmp_path, binary,
                                                                  command, damage):
    run = tmp_path / "run"
    shutil.copytree(made / "a", run)
    named = _damage(damage, run, made / "b")
    (tmp_path / "s.txt").write_text("goto frame 0\n")
    argv = [binary] + COMMANDS[command](str(run), str(tmp_path))
    code, err, cpu, mb = _measured(argv, tmp_path.parent / (tmp_path.name + ".log"))
    assert code == 2, f"{command} read a run with {damage} and exited {code}:\n{err}"
    assert named in err, f"{command}: {err}"
    assert cpu - baseline_cpu < 1.0, f"{command} took {cpu:.2f} CPU s to refuse ({baseline_cpu:.2f} s to start)"
    assert mb - baseline_mb < 100, f"{command} grew to {mb:.0f} MB to refuse ({baseline_mb:.0f} MB at start)"
    # Nothing written: the outputs the commands were given do not exist.
    left = sorted(n for n in os.listdir(tmp_path) if n not in ("run", "s.txt"))
    assert not left, f"{command} left {left}"


@pytest.mark.parametrize("damage", DAMAGE)
def test_the_package_refuses_the_damaged_run(made, tmp_path, damage):
    run = tmp_path / "run"
    shutil.copytree(made / "a", run)
    named = _damage(damage, run, made / "b")
    with pytest.raises(siloscope.SiloscopeError) as e:
        siloscope.read_run(str(run)).trajectory
        siloscope.read_contacts(str(run))
    assert named in str(e.value)


def test_the_undamaged_run_is_read_by_every_command(made, tmp_path, binary):
    """The control: the same commands on the run as written."""
    for name, how in COMMANDS.items():
        if name in ("gallery", "record --compare-run"):
            continue  # they re-simulate or film (seconds): their refusals are what this file tests
        out = tmp_path / name.replace(" ", "_")
        out.mkdir()
        (out / "s.txt").write_text("goto frame 0\n")
        p = subprocess.run([binary] + how(str(made / "a"), str(out)), capture_output=True, text=True)
        assert p.returncode == 0, f"{name}: {p.stderr}"
    siloscope.read_run(str(made / "a")).trajectory
    siloscope.read_contacts(str(made / "a"))
