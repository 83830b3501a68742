#!/usr/bin/env python3
"""The estimator is pure computation.

Why: the same estimator runs on the truck (inside roadloadd), over recordings (roadload analyze),
in the simulator's closed-loop tests and under the fuzzers. It can only give the same answer in all
of them, and be tested without a truck, if it never touches the world: no files, sockets, devices,
threads or clocks. Time comes in with the samples (CaptureTime); I/O stays in drivers/ and
firmware/. So nothing under estimator/ (estimator/core/ included) may include a Linux or POSIX
header or an I/O or threading header, or read a clock, and (given the static libraries) neither
archive may call libc's I/O or clock functions.

Usage: check_estimator_purity.py [--root DIR] [--nm NM] [ARCHIVE ...]
  ARCHIVE: libroadload_estimator.a, libroadload_core.a: also checked with `nm -u`.
Prints `path:line: message` or `archive: symbol` per violation; exit status 1 if any.
"""

import argparse
import os
import re
import subprocess
import sys

import layers_common as common

# Headers that only make sense for a program that talks to the operating system or hardware.
FORBIDDEN_HEADER_PREFIXES = ("sys/", "linux/", "asm/", "netinet/", "arpa/", "net/", "netpacket/",
                             "systemd/", "gpiod", "libudev")
FORBIDDEN_HEADERS = {
    # POSIX and Linux C headers
    "unistd.h", "fcntl.h", "poll.h", "pthread.h", "time.h", "signal.h", "termios.h", "dirent.h",
    "sched.h", "semaphore.h", "mqueue.h", "syslog.h", "pwd.h", "grp.h", "dlfcn.h", "spawn.h",
    "aio.h", "glob.h", "libgen.h", "netdb.h", "ifaddrs.h", "utime.h", "wait.h", "err.h", "gps.h",
    "gpiod.h", "stdio_ext.h", "threads.h",
    # C++ I/O, filesystem, threads and clocks-by-another-name
    "fstream", "iostream", "filesystem", "thread", "mutex", "shared_mutex", "condition_variable",
    "future", "semaphore", "latch", "barrier", "stop_token", "atomic", "execution", "syncstream",
    "print", "ctime", "csignal",
}

# Reading the time or another source of nondeterminism in source text (comments and strings
# blanked). std::chrono itself is fine: durations and the CaptureClock's time_point are data.
FORBIDDEN_CODE = [
    (re.compile(r"\b(system_clock|steady_clock|high_resolution_clock|utc_clock|tai_clock|gps_clock|file_clock)\b"),
     "reads a clock ({0})"),
    (re.compile(r"::\s*now\s*\("), "reads a clock (::now())"),
    (re.compile(r"\b(clock_gettime|gettimeofday|timespec_get|localtime(_r)?)\b"), "reads a clock ({0})"),
    (re.compile(r"\bstd\s*::\s*time\s*\(|(?<![\w.>])(::\s*)?\btime\s*\(\s*(nullptr|NULL|0)\s*\)"),
     "reads a clock ({0})"),
    (re.compile(r"(?<![\w.>])(std\s*)?::\s*clock\s*\("), "reads a clock ({0})"),
    (re.compile(r"(?<![\w.>])(std\s*::\s*)?\b(s?rand)\s*\("), "uses the C library's hidden random state ({0})"),
    (re.compile(r"\brandom_device\b"), "draws nondeterministic random numbers ({0})"),
    (re.compile(r"\bthis_thread\b"), "sleeps or asks for the thread ({0})"),
    (re.compile(r"\b(secure_)?getenv\s*\("), "reads the environment ({0})"),
]

INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*([<"])([^>"\n]+)[>"]', re.MULTILINE)

# Undefined symbols an archive may not have: the C library's I/O, clocks, processes and threads.
# (snprintf, memcpy, strlen, the math functions and the C++ runtime's own symbols are fine.)
FORBIDDEN_SYMBOLS = set("""
open open64 openat openat64 creat close read write pread pread64 pwrite pwrite64 readv writev lseek lseek64
fopen fopen64 fdopen freopen fclose fread fwrite fgets fputs fputc fgetc getc putc putchar puts getchar
printf fprintf vprintf vfprintf dprintf vdprintf scanf fscanf vfscanf fflush fseek fseeko ftell ftello rewind
perror setvbuf tmpfile mkstemp remove rename unlink unlinkat mkdir rmdir chdir getcwd access stat fstat lstat
statx opendir fdopendir readdir closedir truncate ftruncate fsync fdatasync sync
stdin stdout stderr
clock_gettime clock_getres gettimeofday time clock timespec_get localtime localtime_r ftime
socket connect bind listen accept accept4 send sendto sendmsg recv recvfrom recvmsg shutdown setsockopt
getsockopt getaddrinfo ioctl fcntl mmap munmap mprotect poll ppoll select pselect epoll_create epoll_create1
epoll_ctl epoll_wait eventfd timerfd_create timerfd_settime inotify_init inotify_init1 signalfd
sleep usleep nanosleep clock_nanosleep sched_yield pause alarm
pthread_create pthread_join pthread_detach pthread_mutex_lock pthread_mutex_unlock pthread_cond_wait
pthread_cond_signal pthread_once pthread_self pthread_setname_np
fork vfork execv execve execvp execl system popen pclose pipe pipe2 dup dup2 dup3 kill raise signal
sigaction getenv secure_getenv setenv getpid syscall getrandom rand srand random srandom
__printf_chk __fprintf_chk __vfprintf_chk __vprintf_chk __dprintf_chk __read_chk __pread_chk
__fread_chk __fgets_chk __open_2 __open64_2 __openat_2 __openat64_2 __poll_chk __isoc99_scanf
__isoc99_fscanf __isoc99_vfscanf __isoc23_scanf __isoc23_fscanf
""".split())
# The same in the C++ library, by demangled name.
FORBIDDEN_SYMBOL_PATTERNS = [
    re.compile(r"^std::chrono::(_V2::)?(system_clock|steady_clock|high_resolution_clock)::now\b"),
    re.compile(r"^std::(cout|cerr|clog|cin|wcout|wcerr|wclog|wcin)\b"),
    re.compile(r"^std::ios_base::Init::Init\b"),  # a translation unit includes <iostream>
    re.compile(r"^std::(__cxx11::)?basic_(i|o)?fstream<"),
    re.compile(r"^std::basic_filebuf<"),
    re.compile(r"^std::filesystem::"),
    re.compile(r"^std::thread\b"),
    re.compile(r"^std::this_thread::"),
    re.compile(r"^std::random_device::"),
]


def estimator_sources(root):
    return common.walk_files(root, ["estimator"], lambda rel: rel.endswith(common.CXX_EXTENSIONS))


def header_violation(name):
    bare = name.strip()
    if bare in FORBIDDEN_HEADERS or bare.startswith(FORBIDDEN_HEADER_PREFIXES):
        return f"includes <{bare}>: the estimator is pure computation (no OS, I/O, threads or clocks)"
    return None


def check_sources(root):
    violations = []
    for rel in estimator_sources(root):
        text = common.read_text(os.path.join(root, rel))
        without_comments = common.blank_cxx(text, strings=False)
        for m in INCLUDE.finditer(without_comments):
            problem = header_violation(m.group(2))
            if problem:
                violations.append(f"{rel}:{common.line_of(text, m.start())}: {problem}")
        code = common.blank_cxx(text)
        for pattern, message in FORBIDDEN_CODE:
            for m in pattern.finditer(code):
                what = re.sub(r"\s+", "", m.group(0))
                what += ")" if what.endswith("(") else ""
                violation = f"{rel}:{common.line_of(text, m.start())}: {message.format(what)}"
                if violation not in violations:
                    violations.append(violation)
    return violations


def undefined_symbols(nm, archive):
    """Demangled undefined symbols of every member of a static library."""
    out = subprocess.run([nm, "-u", "-C", archive], capture_output=True, text=True, check=True).stdout
    symbols = set()
    for line in out.splitlines():
        parts = line.split(None, 1)
        if len(parts) == 2 and parts[0] in ("U", "w", "v"):
            symbols.add(parts[1].split("@")[0].strip())
    return symbols


def symbol_violation(symbol):
    if symbol in FORBIDDEN_SYMBOLS:
        return True
    return any(p.search(symbol) for p in FORBIDDEN_SYMBOL_PATTERNS)


def check_archives(nm, archives):
    violations = []
    for archive in archives:
        for symbol in sorted(undefined_symbols(nm, archive)):
            if symbol_violation(symbol):
                violations.append(f"{archive}: {symbol}")
    return violations


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    common.add_root_argument(parser)
    parser.add_argument("--nm", default="nm", help="nm for the archives' target (default: nm)")
    parser.add_argument("archives", nargs="*", metavar="ARCHIVE", help="static libraries to check with nm -u")
    args = parser.parse_args()
    common.require_root(parser, args.root, ["estimator"])

    violations = check_sources(args.root)
    violations += check_archives(args.nm, args.archives)
    checked = f"{len(estimator_sources(args.root))} files under estimator/"
    if args.archives:
        checked += f" and {len(args.archives)} archive(s)"
    return common.report("check_estimator_purity", violations, checked)


if __name__ == "__main__":
    sys.exit(main())
