// legacy-fpu-exec: runs a command that cannot read or write any thread's XSAVE state through
// ptrace, so that the User-Mode Linux kernel it starts keeps its guest threads' FPU state in the
// legacy 512-byte FXSAVE area.
//
// Why: UML 6.1 (Debian 12's user-mode-linux) passes ptrace(PTRACE_SETREGSET, NT_X86_XSTATE) a
// buffer sized for AVX, while the host kernel wants its whole XSAVE size; on a host with AVX-512 or
// AMX that call fails with EFAULT and UML panics as soon as init runs ("ptrace set fp regs failed,
// errno = 14"). UML probes XSTATE support once at boot with PTRACE_GETREGSET; when the probe
// fails it uses PTRACE_GETFPREGS/SETFPREGS, which every x86-64 host accepts.
//
// The cost: only x87 and SSE state then survives UML's register switching, so guest programs must
// not use AVX registers. uml-run gives the guest's init (and so every guest process) a
// GLIBC_TUNABLES that makes glibc pick its SSE2 routines; roadload's own code is built for
// baseline x86-64. Without it, glibc's AVX-512 string functions return garbage in the guest.
//
// usage: legacy-fpu-exec COMMAND [ARGS...]
#include <errno.h>
#include <linux/audit.h>
#include <linux/elf.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sys/prctl.h>
#include <sys/ptrace.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstddef>
#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: legacy-fpu-exec COMMAND [ARGS...]\n");
    return 64;
  }
  // The low 32 bits of a system call argument (x86-64 is little-endian).
  constexpr auto arg = [](int i) { return static_cast<unsigned>(offsetof(seccomp_data, args) + 8 * i); };
  // ptrace(PTRACE_GETREGSET or PTRACE_SETREGSET, pid, NT_X86_XSTATE, ...) fails with EIO; every
  // other system call, and every other ptrace request, goes through.
  sock_filter filter[] = {
      BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, arch)),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, AUDIT_ARCH_X86_64, 1, 0),
      BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
      BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(seccomp_data, nr)),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_ptrace, 1, 0),
      BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
      BPF_STMT(BPF_LD | BPF_W | BPF_ABS, arg(0)),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, PTRACE_GETREGSET, 2, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, PTRACE_SETREGSET, 1, 0),
      BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
      BPF_STMT(BPF_LD | BPF_W | BPF_ABS, arg(2)),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, NT_X86_XSTATE, 0, 1),
      BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ERRNO | EIO),
      BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
  };
  const sock_fprog program{static_cast<unsigned short>(sizeof filter / sizeof filter[0]), filter};
  if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0 || prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &program) != 0) {
    std::fprintf(stderr, "legacy-fpu-exec: cannot install the seccomp filter: %s\n", std::strerror(errno));
    return 125;
  }
  execvp(argv[1], argv + 1);
  std::fprintf(stderr, "legacy-fpu-exec: cannot run %s: %s\n", argv[1], std::strerror(errno));
  return 127;
}
