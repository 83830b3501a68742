#!/usr/bin/python3
"""Bad input as a careless or hostile user gives it, case by case: each case damages a copy of a
short simulated drive (or gives a bad option or file) and expects the command's exit status and a
message naming the file, line and field. Exit codes are sysexits for roadload (64 usage, 65 data,
66 missing input; roadloadd: 64 for its command line, 78 for refused settings); 0 where the format allows what is given.
usage: bad-input.py ROADLOAD ROADLOADD CONFIG_DIR"""
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROADLOAD, ROADLOADD, CONFIG = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
work = pathlib.Path(tempfile.mkdtemp(prefix="bad-input."))
base = work / "base"
subprocess.run([ROADLOAD, "simulate", "--scenario", "mnroad-mainline-30mph", "--seed", "9", "--duration", "20", "--out",
                str(base), "-q"], check=True)


def edit_line(name, line, change):
    """A function damaging line `line` (1-based) of stream `name` with `change(text) -> text`."""
    def apply(rec):
        path = rec / name
        lines = path.read_text().splitlines(keepends=True)
        lines[line - 1] = change(lines[line - 1].rstrip("\n")) + "\n"
        path.write_text("".join(lines))
    return apply


def field(name, line, column, value):
    """Sets one CSV field (by column name) of line `line`."""
    def change(text):
        header = (base / name).read_text().splitlines()[0].split(",")
        parts = text.split(",")
        parts[header.index(column)] = value
        return ",".join(parts)
    return edit_line(name, line, change)


def replace_line(name, line, text):
    return edit_line(name, line, lambda _: text)


def meta(text_from, text_to):
    def apply(rec):
        path = rec / "meta.toml"
        t = path.read_text()
        assert text_from in t, text_from
        path.write_text(t.replace(text_from, text_to, 1))
    return apply


def as_segment(n):
    """meta.toml as a logger's segment n of run "ab12" (a simulated run has an id, no segment)."""
    def apply(rec):
        path = rec / "meta.toml"
        t = re.sub(r"(?m)^recording_id = .*\n", "", path.read_text())
        path.write_text(t.replace("version = 1\n", f'version = 1\nrecording_id = "ab12"\nsegment = {n}\n', 1))
    return apply


def append_meta(text):
    def apply(rec):
        with open(rec / "meta.toml", "a") as f:
            f.write(text)
    return apply


def replace_with_dir(name):
    def apply(rec):
        (rec / name).unlink()
        (rec / name).mkdir()
    return apply


def drop_column(name, column):
    def apply(rec):
        rows = [l.split(",") for l in (rec / name).read_text().splitlines()]
        i = rows[0].index(column)
        (rec / name).write_text("".join(",".join(r[:i] + r[i + 1:]) + "\n" for r in rows))
    return apply


def long_line(name, line, size):
    def apply(rec):
        path = rec / name
        lines = path.read_text().splitlines(keepends=True)
        lines.insert(line - 1, "7" * size + "\n")
        path.write_text("".join(lines))
    return apply


def write_file(relative, text):
    def apply(_rec):
        p = work / relative
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    return apply


FRAME = "(1413792001.000000) can0 18FEF100#0011223344556677"
ANALYZE = ["analyze", "{rec}", "--out", "{work}/out"]
VEHICLE = (CONFIG / "vehicles" / "mnroad-truck.toml").read_text()
ROUTE = (CONFIG / "routes" / "flat-track.toml").read_text()

# (name, damage, command, exit status, what stderr must say[, what the results must hold])
CASES = [
    # can.log
    ("can.log garbage line", replace_line("can.log", 3, "garbage"), ANALYZE, 65, r"can\.log:3: timestamp: expected a candump"),
    ("can.log is a directory", replace_with_dir("can.log"), ANALYZE, 65, r"can\.log:1: Is a directory"),
    ("can.log 10 MB line", long_line("can.log", 100, 10_000_000), ANALYZE, 65, r"can\.log:100: line longer than 65536 bytes, skipped"),
    ("can.log identifier not hex", edit_line("can.log", 5, lambda t: t.replace(" can0 ", " can0 X", 1)[:-1]), ANALYZE, 65,
     r"can\.log:5: identifier"),
    ("can.log odd data digits", edit_line("can.log", 6, lambda t: t + "F"), ANALYZE, 65, r"can\.log:6: data: odd number of hex digits"),
    ("can.log stamp of 3 digits", replace_line("can.log", 7, "(1413792001.000) can0 18FEF100#00"), ANALYZE, 65,
     r"can\.log:7: timestamp: fraction must have 6 or 9 digits"),
    ("can.log 11-bit id above 7FF", replace_line("can.log", 8, "(1413792001.000000) can0 FFF#00"), ANALYZE, 65,
     r"can\.log:8: identifier: 11-bit identifier above 0x7FF"),
    ("can.log no interface", replace_line("can.log", 9, "(1413792001.000000) 18FEF100#00"), ANALYZE, 65, r"can\.log:9: interface"),
    ("can.log nine data bytes", replace_line("can.log", 10, FRAME + "88"), ANALYZE, 65, r"can\.log:10: data: too many data bytes"),
    ("can.log stamp beyond 2255", replace_line("can.log", 11, "(99999999999.000000) can0 18FEF100#00"), ANALYZE, 65,
     r"can\.log:11: timestamp: seconds beyond"),
    # accel.csv
    ("accel NaN", field("accel.csv", 4, "x_mps2", "nan"), ANALYZE, 65, r"accel\.csv:4: x_mps2: expected a finite number"),
    ("accel inf", field("accel.csv", 5, "y_mps2", "inf"), ANALYZE, 65, r"accel\.csv:5: y_mps2: expected a finite number"),
    ("accel extra field", edit_line("accel.csv", 6, lambda t: t + ",1"), ANALYZE, 65, r"accel\.csv:6: row: expected 5 fields, found 6"),
    ("accel unknown sensor", field("accel.csv", 7, "sensor", "300"), ANALYZE, 65, r"accel\.csv:7: sensor: out of range 0\.\.255"),
    ("accel stamp INT64_MAX", field("accel.csv", 8, "t_ns", "9223372036854775807"), ANALYZE, 65, r"accel\.csv:8: t_ns: stamp out of range"),
    ("accel stamp INT64_MIN", field("accel.csv", 9, "t_ns", "-9223372036854775808"), ANALYZE, 65, r"accel\.csv:9: t_ns: stamp out of range"),
    ("accel 100,000 g", field("accel.csv", 10, "z_mps2", "1e6"), ANALYZE, 65, r"accel\.csv:10: z_mps2: acceleration out of range"),
    ("accel word for number", field("accel.csv", 11, "x_mps2", "zero"), ANALYZE, 65, r"accel\.csv:11: x_mps2: expected a finite number"),
    ("accel missing column", drop_column("accel.csv", "z_mps2"), ANALYZE, 65, r"accel\.csv:1: z_mps2: required column missing"),
    ("accel 1 MB line", long_line("accel.csv", 20, 1_500_000), ANALYZE, 65, r"accel\.csv:20: line longer than 65536 bytes"),
    ("accel upside down is named, not refused", lambda rec: (rec / "accel.csv").write_text(
        "".join((l if i == 0 or l.startswith("#") else ",".join(l.split(",")[:4] + [str(-float(l.split(",")[4]))])) + "\n"
                for i, l in enumerate((rec / "accel.csv").read_text().splitlines()))),
     ANALYZE, 0, r"accelerometer \S+ \(tractor-front-axle-left\): mean z -9\.\d+ m/s\^2 over \d+ samples.*upside down",
     lambda work: '"accelerometer_warnings": ["accelerometer' in (work / "out" / "trip.json").read_text()),
    # gnss.csv
    ("gnss latitude 95", field("gnss.csv", 3, "lat_deg", "95"), ANALYZE, 65, r"gnss\.csv:3: lat_deg: latitude out of range"),
    ("gnss longitude 200", field("gnss.csv", 4, "lon_deg", "200"), ANALYZE, 65, r"gnss\.csv:4: lon_deg: longitude out of range"),
    ("gnss speed -1", field("gnss.csv", 5, "speed_mps", "-1"), ANALYZE, 65, r"gnss\.csv:5: speed_mps: speed out of range"),
    ("gnss mode 9", field("gnss.csv", 6, "mode", "9"), ANALYZE, 65, r"gnss\.csv:6: mode: out of range 0\.\.5"),
    ("gnss height 1e6", field("gnss.csv", 7, "alt_m", "1e6"), ANALYZE, 65, r"gnss\.csv:7: alt_m: height out of range"),
    ("gnss course 400", field("gnss.csv", 8, "course_deg", "400"), ANALYZE, 65, r"gnss\.csv:8: course_deg: course out of range"),
    ("gnss HDOP -1", field("gnss.csv", 9, "hdop", "-1"), ANALYZE, 65, r"gnss\.csv:9: hdop: HDOP out of range"),
    ("gnss UTC negative", field("gnss.csv", 10, "utc_ns", "-1"), ANALYZE, 65, r"gnss\.csv:10: utc_ns: UTC out of range"),
    ("gnss too few fields", edit_line("gnss.csv", 11, lambda t: ",".join(t.split(",")[:4])), ANALYZE, 65,
     r"gnss\.csv:11: row: expected 9 fields, found 4"),
    ("gnss missing latitude column", drop_column("gnss.csv", "lat_deg"), ANALYZE, 65, r"gnss\.csv:1: lat_deg: required column missing"),
    ("gnss without UTC or course is read", lambda rec: (drop_column("gnss.csv", "utc_ns")(rec), drop_column("gnss.csv", "course_deg")(rec)),
     ANALYZE, 0, r""),
    # weather.csv
    ("weather -300 C", field("weather.csv", 3, "air_temp_c", "-300"), ANALYZE, 65, r"weather\.csv:3: air_temp_c: air temperature out of range"),
    ("weather wind 1e9", field("weather.csv", 4, "wind_speed_mps", "1e9"), ANALYZE, 65, r"weather\.csv:4: wind_speed_mps: wind speed out of range"),
    ("weather negative pressure", field("weather.csv", 5, "pressure_pa", "-5"), ANALYZE, 65, r"weather\.csv:5: pressure_pa: pressure out of range"),
    ("weather direction 400", field("weather.csv", 6, "wind_from_deg", "400"), ANALYZE, 65, r"weather\.csv:6: wind_from_deg: wind direction out of range"),
    ("weather station 256", field("weather.csv", 7, "station", "256"), ANALYZE, 65, r"weather\.csv:7: station: out of range 0\.\.255"),
    # meta.toml
    ("meta mass as text", meta("mass_kg = ", 'mass_kg = "heavy" #'), ANALYZE, 65, r"meta\.toml:\d+: vehicle\.mass_kg: expected a number"),
    ("meta vehicle not a table", lambda rec: (rec / "meta.toml").write_text('format = "roadload-recording"\nversion = 1\nvehicle = 5\n'),
     ANALYZE, 65, r"meta\.toml:3: vehicle: expected a table"),
    ("meta clock not a table", lambda rec: (rec / "meta.toml").write_text('format = "roadload-recording"\nversion = 1\nclock = "x"\n'),
     ANALYZE, 65, r"meta\.toml:3: clock: expected a table"),
    ("meta is a directory", replace_with_dir("meta.toml"), ANALYZE, 66, r"meta\.toml: Is a directory"),
    ("meta version 2", meta("version = 1", "version = 2"), ANALYZE, 65, r"meta\.toml:\d+: version: unsupported format version"),
    ("meta negative mass", meta("mass_kg = ", "mass_kg = -5 #"), ANALYZE, 65, r"meta\.toml:\d+: vehicle\.mass_kg: a mass must lie"),
    ("meta driven before it -600 s", meta("driven_before_s = ", "driven_before_s = -600 #"), ANALYZE, 65,
     r"meta\.toml:\d+: vehicle\.driven_before_s: the driving before the recording must lie 0-86,400 s"),
    ("meta TOML syntax", append_meta("[[sensor\n"), ANALYZE, 65, r"meta\.toml:\d+: toml:"),
    ("meta non-ASCII key", append_meta("\u03a6 = 1\n"), ANALYZE, 65, r"meta\.toml:\d+"),
    ("meta sensor id text", append_meta('[[sensor]]\nid = "zero"\nname = "a"\nkind = "b"\n'), ANALYZE, 65, r"meta\.toml:\d+: sensor\[\d+\]\.id"),
    # the command line and the recording as a whole
    ("no such recording", None, ["analyze", "{work}/absent/recording", "--out", "{work}/out"], 66, r"absent/recording"),
    ("a text file as the recording", write_file("notes.txt", "remember the milk\n"), ["analyze", "{work}/notes.txt", "--out", "{work}/out"],
     65, r"notes\.txt:1: timestamp"),
    ("two recordings, not one run's segments", None, ["analyze", "{rec}", "{rec}", "--out", "{work}/out"], 64,
     r"meta\.toml: recording_id: not a segment of a logger's drive"),
    ("one segment given twice", as_segment(1),
     ["analyze", "{rec}", "{rec}", "--out", "{work}/out"], 64, r"segment: segment 1 given twice"),
    ("a segment and a log joined", as_segment(1),
     ["decode", "{rec}", "{rec}/can.log"], 64, r"can\.log: not a recording folder"),
    ("segment number 0", as_segment(0), ANALYZE, 65,
     r"meta\.toml:\d+: segment: expected a segment number from 1"),
    ("decode of a folder without can.log", lambda rec: (rec / "can.log").unlink(), ["decode", "{rec}"], 66,
     r"without-can-log: no can\.log in the folder"),
    ("analyze without --out", None, ["analyze", "{rec}"], 64, r"--out is required"),
    ("analyze --mass not a number", None, ANALYZE + ["--mass", "heavy"], 64, r"--mass: 'heavy' is not a finite number"),
    ("analyze --mass 1e9 kg", None, ANALYZE + ["--mass", "1e9"], 64, r"--mass: '1e9' is not a finite number in"),
    ("analyze unknown option", None, ANALYZE + ["--fast"], 64, r"--fast: unknown option"),
    ("psd two recordings", None, ["psd", "{rec}", "{rec}"], 64, r"not a segment of a logger's drive"),
    ("collect a recording, not results", None, ["collect", "{rec}", "--db", "{work}/fleet.db"], 66, r"cells\.csv"),
    ("network of no database", None, ["network", "--db", "{work}/absent.db", "-o", "{work}/net"], 66,
     r"absent\.db: cannot open the SQLite database"),
    ("collect into no known database", None, ["collect", "{rec}", "--db", "mysql://host/roads"], 73, r"not a database URL"),
    ("decode garbage", write_file("garbage.log", "garbage\n"), ["decode", "{work}/garbage.log"], 65, r"garbage\.log:1: timestamp"),
    ("decode missing file", None, ["decode", "{work}/missing.log"], 66, r"missing\.log"),
    ("simulate unknown scenario", None, ["simulate", "--scenario", "no-such", "--out", "{work}/s"], 66, r"no-such"),
    ("simulate unknown effect", None, ["simulate", "--scenario", "th66-55mph", "--out", "{work}/s", "--effect", "gremlins=1"], 64,
     r"gremlins"),
    ("simulate effect magnitude text", None, ["simulate", "--scenario", "th66-55mph", "--out", "{work}/s", "--effect", "wind-gusts=lots"],
     64, r"lots"),
    ("gap --holdout wrong", None, ["gap", "--real", "{rec}", "--holdout", "halves"], 64, r"--holdout: expected cells or runs"),
    ("gap --noise-runs 1000", None, ["gap", "--real", "{rec}", "--noise-runs", "1000"], 64, r"--noise-runs"),
    ("vehicle CdA as text", write_file("bad-vehicle.toml", VEHICLE.replace("cda_m2 = 6.2", 'cda_m2 = "big"', 1)),
     ANALYZE + ["--vehicle", "{work}/bad-vehicle.toml"], 65, r"bad-vehicle\.toml:\d+: body\.cda_m2"),
    ("route CRR NaN", write_file("bad-route.toml", ROUTE.replace("default_crr = 0.0055", "default_crr = nan", 1)),
     ANALYZE + ["--route", "{work}/bad-route.toml"], 65, r"bad-route\.toml:\d+: default_crr"),
    ("route missing", None, ANALYZE + ["--route", "{work}/no-route.toml"], 66, r"no-route\.toml"),
    # roadloadd's settings
    ("roadloadd option taken as a value", None, ["@roadloadd", "--can", "--no-gnss"], 64, r"--can: needs IFACE, not the option '--no-gnss'"),
    ("roadloadd infinite segments", write_file("inf.toml", "[recording]\nsegment_max_mib = inf\nquota_mib = inf\n"),
     ["@roadloadd", "--config", "{work}/inf.toml"], 78, r"inf\.toml:2: recording\.segment_max_mib: expected a finite number"),
    ("roadloadd 2 EiB segments", write_file("huge.toml", "[recording]\nsegment_max_mib = 2e12\nquota_mib = 4e12\n"),
     ["@roadloadd", "--config", "{work}/huge.toml"], 78, r"recording\.segment_max_mib: expected 1 to 1048576"),
    ("roadloadd replay of nothing", None, ["@roadloadd", "--replay", "{work}/nothing"], 78, r"replay\.recording: .* does not exist"),
    ("roadloadd replay of a can.log alone", None, ["@roadloadd", "--replay", "{rec}/can.log"], 78, r"not a recording folder"),
    ("roadloadd replay rate text", None, ["@roadloadd", "--replay-rate", "fast"], 64, r"--replay-rate: 'fast' is not a finite number"),
    ("roadloadd unknown key", write_file("typo.toml", "[recording]\nfsync_intervall_s = 3\n"), ["@roadloadd", "--config", "{work}/typo.toml"],
     78, r"fsync_intervall_s"),
]


def run(case):
    name, damage, argv, want_rc, want, *check = case  # check: what the results must hold
    rec = work / re.sub(r"[^a-z0-9]+", "-", name.lower())
    shutil.copytree(base, rec)
    if damage is not None:
        damage(rec)
    args = [a.format(rec=rec, work=work) for a in argv]
    program = ROADLOADD if args[0] == "@roadloadd" else ROADLOAD
    args = args[1:] if args[0] == "@roadloadd" else args
    p = subprocess.run([program] + args, capture_output=True, text=True, timeout=120)
    problems = []
    if p.returncode != want_rc:
        problems.append(f"exit {p.returncode}, expected {want_rc}")
    if want and not re.search(want, p.stderr):
        problems.append(f"stderr lacks /{want}/")
    if p.returncode < 0:
        problems.append(f"killed by signal {-p.returncode}")
    if check and p.returncode == 0 and not check[0](work):
        problems.append("the results do not say it")
    shutil.rmtree(rec, ignore_errors=True)
    return problems, p.stderr


failed = 0
for case in CASES:
    problems, stderr = run(case)
    if problems:
        failed += 1
        tail = stderr.strip().splitlines()[-3:]
        print(f"FAIL {case[0]}: {'; '.join(problems)}\n     stderr: {' | '.join(tail)}")
shutil.rmtree(work, ignore_errors=True)
print(f"bad-input: {len(CASES)} cases, {failed} failed")
sys.exit(1 if failed else 0)
