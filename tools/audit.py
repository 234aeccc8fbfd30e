#!/usr/bin/env python3
"""Register/load audit of compiled CUDA kernels, read from SASS (no GPU needed).

For every function with machine code for the chosen architecture (sm_90 by
default) in an executable, object file or cubin, it reports the columns of the
thesis's Tables 4 to 6: registers, stack frame and spills, local/global/
generic/shared loads and stores, constant-bank reads and floating-point
instructions by kind.

Resources come from `cuobjdump -res-usage`, instruction counts from
`cuobjdump -sass`. Counts are STATIC: each SASS instruction is counted once
where it appears in the code, whatever the loop trip counts or branches taken
at run time. Spill bytes are not stored in the binary; pass the compiler's
`-Xptxas -v` output with --ptxas-log to get them.

Python API (stdlib only):
    audit(binary, arch="sm_90", ptxas_log=None) -> dict[name, KernelStats]
    audit_text(res_text, sass_text, ptxas_text=None, arch="sm_90", demangle=...)
    parse_res_usage(text, arch) / parse_sass(text, arch) / parse_ptxas_log(text, arch)
    select(stats, regex), format_table(stats), format_diff(a, b), to_json(stats)
"""

import argparse
import dataclasses
import json
import os
import re
import shutil
import subprocess
import sys
from collections import Counter

COUNTING_NOTE = ("static counts: each SASS instruction counted once where it appears "
                 "(not weighted by loop trips or branches taken)")


class AuditError(Exception):
    """A problem the user must fix (missing tool, bad binary, no match)."""


# --- results ----------------------------------------------------------------
@dataclasses.dataclass
class KernelStats:
    """Everything the audit knows about one function. Resource fields are None
    when -res-usage did not list the function; spill fields are None unless a
    ptxas log was given. Counts are static SASS occurrences."""
    name: str
    mangled: str
    registers: int = None
    stack: int = None
    shared: int = None  # bytes; on sm_90 cuobjdump includes the 1 KiB system reserve
    local: int = None
    constant: dict = dataclasses.field(default_factory=dict)
    spill_stores: int = None
    spill_loads: int = None
    instructions: int = 0
    local_loads: int = 0
    local_stores: int = 0
    global_loads: int = 0
    global_stores: int = 0
    generic_loads: int = 0
    generic_stores: int = 0
    shared_loads: int = 0
    shared_stores: int = 0
    atomics: int = 0
    const_reads: int = 0  # instructions with a c[..][..] operand, LDC/ULDC included
    const_loads: int = 0  # LDC and ULDC alone
    fp32_add: int = 0
    fp32_mul: int = 0
    fp32_fma: int = 0
    fp64_add: int = 0
    fp64_mul: int = 0
    fp64_fma: int = 0
    special: int = 0  # MUFU (sin, cos, rsqrt, rcp, ex2, lg2, ...)
    convert: int = 0  # F2F, F2I, I2F, F2IP, I2FP, F2FP, FRND
    opcodes: dict = dataclasses.field(default_factory=dict)  # base opcode -> count

    @property
    def fp_arith(self):
        """Floating-point add/mul/fma instructions, both precisions (the
        thesis's "Flops" column counted one per instruction the same way)."""
        return (self.fp32_add + self.fp32_mul + self.fp32_fma
                + self.fp64_add + self.fp64_mul + self.fp64_fma)

    def as_dict(self):
        d = dataclasses.asdict(self)
        d["fp_arith"] = self.fp_arith
        d["constant"] = {str(k): v for k, v in self.constant.items()}
        return d


# The static counters are the fields that start at 0.
COUNT_FIELDS = tuple(f.name for f in dataclasses.fields(KernelStats) if f.default == 0)


# --- instruction classification ---------------------------------------------
# Base opcode (text before the first '.') -> the counters it adds to. LDGSTS
# (async copy global->shared) both reads global and writes shared memory.
OPCODE_COUNTERS = {
    "LDL": ("local_loads",), "STL": ("local_stores",),
    "LDG": ("global_loads",), "STG": ("global_stores",),
    "LDGSTS": ("global_loads", "shared_stores"),
    "LD": ("generic_loads",), "ST": ("generic_stores",),
    "LDS": ("shared_loads",), "LDSM": ("shared_loads",),
    "STS": ("shared_stores",), "STSM": ("shared_stores",),
    "ATOM": ("atomics",), "ATOMG": ("atomics",), "ATOMS": ("atomics",),
    "RED": ("atomics",), "REDG": ("atomics",),
    "LDC": ("const_loads",), "ULDC": ("const_loads",),
    "FADD": ("fp32_add",), "FADD32I": ("fp32_add",),
    "FMUL": ("fp32_mul",), "FMUL32I": ("fp32_mul",),
    "FFMA": ("fp32_fma",), "FFMA32I": ("fp32_fma",),
    "DADD": ("fp64_add",), "DMUL": ("fp64_mul",), "DFMA": ("fp64_fma",),
    "MUFU": ("special",),
    "F2F": ("convert",), "F2I": ("convert",), "I2F": ("convert",),
    "F2IP": ("convert",), "I2FP": ("convert",), "F2FP": ("convert",),
    "FRND": ("convert",),
}

# One instruction in cuobjdump or nvdisasm output: "/*0a30*/  @!P0 FADD R1, ... ;"
_INSN_RE = re.compile(r"^\s*/\*[0-9a-fA-F]+\*/\s*\{?\s*(?:@!?U?P[T0-9]+\s+)?([A-Z][A-Z0-9_.]*)([^;]*);")
# A constant-bank operand: c[0x0][0x210], or the bindless cx[UR4][...]. The \b
# keeps "desc[UR4]" from matching.
_CONST_RE = re.compile(r"\bcx?\[")
_FUNC_CUOBJDUMP_RE = re.compile(r"^\s*Function\s*:\s*(\S+)\s*$")
_FUNC_NVDISASM_RE = re.compile(r"^\.text\.(\S+):\s*$")
_ARCH_RE = re.compile(r"^\s*(?:arch\s*=\s*|code for\s+|\.target\s+)(sm_\d+[a-z]?)\b")


def classify(opcode, operands):
    """Counter names one instruction adds to (opcode may carry .modifiers)."""
    base = opcode.split(".", 1)[0]
    names = list(OPCODE_COUNTERS.get(base, ()))
    if _CONST_RE.search(operands) or base in ("LDC", "ULDC"):
        names.append("const_reads")
    return names


def _arch_filter(text, arch):
    """Yield the lines of text that belong to code for `arch`.

    cuobjdump prints "arch = sm_XX" per fatbin entry and "code for sm_XX" before
    SASS; a bare cubin's res-usage names no architecture, so lines before any
    marker are kept."""
    current = None
    for line in text.splitlines():
        m = _ARCH_RE.match(line)
        if m:
            current = m.group(1)
            continue
        if current is None or arch is None or current == arch:
            yield line


def parse_sass(text, arch="sm_90"):
    """Static instruction counts per function from `cuobjdump -sass` or
    `nvdisasm` text. Returns a list of (mangled_name, Counter) in order of
    appearance (a name may repeat when several fatbins hold it). The Counter
    holds the COUNT_FIELDS plus "op:<BASE>" per base opcode."""
    functions = []
    current = None
    for line in _arch_filter(text, arch):
        m = _FUNC_CUOBJDUMP_RE.match(line) or _FUNC_NVDISASM_RE.match(line)
        if m:
            current = Counter({f: 0 for f in COUNT_FIELDS})
            functions.append((m.group(1), current))
            continue
        if current is None:
            continue
        m = _INSN_RE.match(line)
        if not m:
            continue
        opcode, operands = m.group(1), m.group(2)
        base = opcode.split(".", 1)[0]
        if base == "NOP":  # alignment padding, not work
            continue
        current["instructions"] += 1
        current["op:" + base] += 1
        for name in classify(opcode, operands):
            current[name] += 1
    return functions


_RES_FUNC_RE = re.compile(r"^\s*Function\s+(\S+?):\s*$")
_RES_PAIR_RE = re.compile(r"([A-Z]+)(?:\[(\d+)\])?:(\d+)")


def parse_res_usage(text, arch="sm_90"):
    """Resources per function from `cuobjdump -res-usage` text. Returns a list
    of (mangled_name, dict) with keys registers, stack, shared, local, texture,
    surface, sampler (ints) and constant ({bank: bytes})."""
    keys = {"REG": "registers", "STACK": "stack", "SHARED": "shared", "LOCAL": "local",
            "TEXTURE": "texture", "SURFACE": "surface", "SAMPLER": "sampler"}
    functions = []
    pending = None
    for line in _arch_filter(text, arch):
        m = _RES_FUNC_RE.match(line)
        if m:
            pending = m.group(1)
            continue
        if pending is None:
            continue
        res = {"constant": {}}
        for key, bank, value in _RES_PAIR_RE.findall(line):
            if key == "CONSTANT":
                res["constant"][int(bank or 0)] = int(value)
            elif key in keys:
                res[keys[key]] = int(value)
        functions.append((pending, res))
        pending = None
    return functions


_PTXAS_ARCH_RE = re.compile(r"Compiling entry function '[^']*' for '(sm_\d+[a-z]?)'")
_PTXAS_PROPS_RE = re.compile(r"Function properties for (\S+)")
_PTXAS_SPILL_RE = re.compile(
    r"(\d+) bytes stack frame, (\d+) bytes spill stores, (\d+) bytes spill loads")


def parse_ptxas_log(text, arch="sm_90"):
    """Stack frame and spill bytes per function from `-Xptxas -v` output:
    {mangled_name: {"stack_frame", "spill_stores", "spill_loads"}}. A build for
    several architectures lists each function once per architecture; the
    "Compiling entry function ... for 'sm_XX'" lines say which."""
    result = {}
    current_arch, pending = None, None
    for line in text.splitlines():
        m = _PTXAS_ARCH_RE.search(line)
        if m:
            current_arch = m.group(1)
            continue
        m = _PTXAS_PROPS_RE.search(line)
        if m:
            pending = m.group(1)
            continue
        m = _PTXAS_SPILL_RE.search(line)
        if m and pending and (current_arch is None or arch is None or current_arch == arch):
            result[pending] = {"stack_frame": int(m.group(1)), "spill_stores": int(m.group(2)),
                               "spill_loads": int(m.group(3))}
        pending = None
    return result


def _tool_dirs():
    """Directories to look in for CUDA binaries, besides PATH: the toolkit
    and the bin folders of NVIDIA's pip wheels (nvidia-cuda-cuobjdump)."""
    dirs = [os.path.join(os.environ[v], "bin") for v in ("CUDA_HOME", "CUDA_PATH")
            if os.environ.get(v)]
    dirs.append("/usr/local/cuda/bin")
    for entry in sys.path:
        nvidia = os.path.join(entry or ".", "nvidia")
        if os.path.isdir(nvidia):
            dirs += sorted(os.path.join(nvidia, d, "bin") for d in os.listdir(nvidia))
    return dirs


def find_tool(name, env_var=None):
    """Absolute path of a CUDA tool, or None. env_var overrides the search."""
    if env_var and os.environ.get(env_var):
        path = os.environ[env_var]
        return path if os.access(path, os.X_OK) else None
    found = shutil.which(name)
    if found:
        return found
    for d in _tool_dirs():
        path = os.path.join(d, name)
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    return None


def demangle(names):
    """{mangled: readable} using cu++filt if present, else c++filt; names a
    demangler cannot read (or all, with no demangler) map to themselves."""
    names = list(dict.fromkeys(names))
    # binutils first: cu++filt spells template parameters differently (T1 *).
    tool = shutil.which("c++filt") or find_tool("cu++filt")
    result = {n: n for n in names}
    if tool and names:
        try:
            out = subprocess.run([tool], input="\n".join(names) + "\n", capture_output=True,
                                 text=True, check=True).stdout.splitlines()
        except (OSError, subprocess.CalledProcessError):
            return result
        if len(out) == len(names):
            result.update({n: d.strip() or n for n, d in zip(names, out)})
    return result


def audit_text(res_text, sass_text, ptxas_text=None, arch="sm_90", demangle=demangle):
    """Combine captured tool outputs into {readable_name: KernelStats}.

    The i-th occurrence of a mangled name in the SASS pairs with its i-th
    occurrence in -res-usage. Identical repeats (one kernel in several
    fatbins) collapse to one entry; differing ones get " [2]", " [3]"..."""
    resources = {}
    for mangled, res in parse_res_usage(res_text, arch):
        resources.setdefault(mangled, []).append(res)
    spills = parse_ptxas_log(ptxas_text, arch) if ptxas_text else {}
    sass = parse_sass(sass_text, arch)
    readable = demangle([m for m, _ in sass])
    stats = {}
    seen = Counter()
    for mangled, counts in sass:
        res_list = resources.get(mangled, [])
        res = res_list[seen[mangled]] if seen[mangled] < len(res_list) else {}
        seen[mangled] += 1
        spill = spills.get(mangled, {})
        ks = KernelStats(
            name=readable.get(mangled, mangled), mangled=mangled,
            registers=res.get("registers"), stack=res.get("stack"), shared=res.get("shared"),
            local=res.get("local"), constant=res.get("constant", {}),
            spill_stores=spill.get("spill_stores"), spill_loads=spill.get("spill_loads"),
            opcodes={k[3:]: v for k, v in sorted(counts.items()) if k.startswith("op:")},
            **{f: counts[f] for f in COUNT_FIELDS})
        key, n = ks.name, 1
        while key in stats and stats[key] != dataclasses.replace(ks, name=stats[key].name):
            n += 1
            key = "%s [%d]" % (ks.name, n)
        if key not in stats:
            ks.name = key
            stats[key] = ks
    return stats


def _run(cmd, tool_dir):
    # cuobjdump -sass runs nvdisasm, which the pip wheels put beside it.
    env = dict(os.environ)
    env["PATH"] = tool_dir + os.pathsep + env.get("PATH", "")
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    except OSError as e:
        raise AuditError("cannot run %s: %s" % (cmd[0], e))
    if proc.returncode != 0:
        msg = (proc.stderr or proc.stdout).strip()
        raise AuditError("%s failed (exit %d): %s" % (" ".join(cmd), proc.returncode, msg))
    return proc.stdout


def _cuobjdump_tool(binary):
    """The cuobjdump to run on `binary`, after checking the file can be read."""
    if not os.path.isfile(binary):
        raise AuditError("no such file: %s" % binary)
    if not os.access(binary, os.R_OK):
        raise AuditError("cannot read %s" % binary)
    tool = find_tool("cuobjdump", "CUOBJDUMP")
    if tool is None:
        raise AuditError("cuobjdump not found: install the CUDA toolkit (or "
                         "`pip install nvidia-cuda-cuobjdump nvidia-cuda-nvdisasm`), "
                         "put it on PATH, or set CUOBJDUMP")
    return tool


def audit(binary, arch="sm_90", ptxas_log=None):
    """Audit a binary: {readable_name: KernelStats} for every function with
    `arch` machine code. Raises AuditError with a clear message on failure."""
    tool = _cuobjdump_tool(binary)
    ptxas_text = None
    if ptxas_log:
        try:
            with open(ptxas_log) as f:
                ptxas_text = f.read()
        except OSError as e:
            raise AuditError("cannot read ptxas log %s: %s" % (ptxas_log, e.strerror))
    tool_dir = os.path.dirname(tool)
    res_text = _run([tool, "-arch", arch, "-res-usage", binary], tool_dir)
    sass_text = _run([tool, "-arch", arch, "-sass", binary], tool_dir)
    stats = audit_text(res_text, sass_text, ptxas_text, arch)
    if not stats:
        raise AuditError("%s holds no %s machine code (SASS)" % (binary, arch))
    return stats


def sass_listing(binary, arch="sm_90"):
    """{mangled name: [(base opcode, operands)]} in program order, NOP padding
    left out: for claims about the order of instructions, which counts lose."""
    tool = _cuobjdump_tool(binary)
    text = _run([tool, "-arch", arch, "-sass", binary], os.path.dirname(tool))
    listing, current = {}, None
    for line in _arch_filter(text, arch):
        m = _FUNC_CUOBJDUMP_RE.match(line)
        if m:
            current = listing.setdefault(m.group(1), [])
            continue
        m = _INSN_RE.match(line)
        if m and current is not None and not m.group(1).startswith("NOP"):
            current.append((m.group(1).split(".", 1)[0], m.group(2)))
    return listing


def select(stats, regex):
    """The entries whose readable or mangled name matches regex (re.search)."""
    pattern = re.compile(regex)
    return {k: s for k, s in stats.items() if pattern.search(k) or pattern.search(s.mangled)}


def find_kernel(stats, name):
    """One kernel by exact readable/mangled name, else by a regex that must
    match exactly one."""
    for key, s in stats.items():
        if name in (key, s.mangled):
            return s
    matches = select(stats, name)
    if len(matches) != 1:
        raise AuditError("%r matches %s kernels%s" % (
            name, len(matches) or "no",
            ": " + "; ".join(matches) if matches else ""))
    return next(iter(matches.values()))


# --- output -----------------------------------------------------------------
def _opt(v):
    return "-" if v is None else str(v)


# (header, how to get the cell) for the table; the legend explains them.
COLUMNS = (
    ("Regs", lambda s: _opt(s.registers)),
    ("Stack", lambda s: _opt(s.stack)),
    ("Spill", lambda s: "-" if s.spill_stores is None
        else "%d/%d" % (s.spill_stores, s.spill_loads)),
    ("Smem", lambda s: _opt(s.shared)),
    ("LDL", lambda s: s.local_loads), ("STL", lambda s: s.local_stores),
    ("LDG", lambda s: s.global_loads), ("STG", lambda s: s.global_stores),
    ("LD", lambda s: s.generic_loads), ("ST", lambda s: s.generic_stores),
    ("LDS", lambda s: s.shared_loads), ("STS", lambda s: s.shared_stores),
    ("Atom", lambda s: s.atomics),
    ("Cread", lambda s: s.const_reads),
    ("F+", lambda s: s.fp32_add), ("F*", lambda s: s.fp32_mul), ("Ffma", lambda s: s.fp32_fma),
    ("D+", lambda s: s.fp64_add), ("D*", lambda s: s.fp64_mul), ("Dfma", lambda s: s.fp64_fma),
    ("MUFU", lambda s: s.special), ("Cvt", lambda s: s.convert),
    ("Insts", lambda s: s.instructions),
)

LEGEND = (
    "Regs registers, Stack stack frame bytes, Spill spill store/load bytes (needs --ptxas-log),",
    "Smem shared bytes; loads/stores: LDL/STL local, LDG/STG global, LD/ST generic, LDS/STS shared;",
    "Atom atomics, Cread instructions reading a constant bank, F/D fp32/fp64 add mul fma,",
    "MUFU special functions, Cvt conversions, Insts all instructions but NOP.",
)


def format_table(stats, arch="sm_90"):
    """An aligned text table, one row per kernel, names last so numbers align."""
    rows = [[str(get(s)) for _, get in COLUMNS] + [s.name] for s in stats.values()]
    header = [h for h, _ in COLUMNS] + ["Kernel"]
    widths = [max(len(r[i]) for r in rows + [header]) for i in range(len(COLUMNS))]

    def line(cells):
        return "  ".join(c.rjust(w) for c, w in zip(cells, widths)) + "  " + cells[-1]

    out = ["# %s, %s" % (arch, COUNTING_NOTE)] + ["# " + l for l in LEGEND] + [line(header)]
    out += [line(r) for r in rows]
    return "\n".join(out)


DIFF_FIELDS = (("registers", "stack", "shared", "local", "spill_stores", "spill_loads")
               + COUNT_FIELDS + ("fp_arith",))


def diff(a, b):
    """[(field, value_a, value_b, b - a or None)] over DIFF_FIELDS."""
    rows = []
    for f in DIFF_FIELDS:
        va, vb = getattr(a, f), getattr(b, f)
        rows.append((f, va, vb, None if va is None or vb is None else vb - va))
    return rows


def format_diff(a, b, arch="sm_90"):
    """Two kernels side by side with a B-A column."""
    rows = [(f, _opt(va), _opt(vb), "-" if d is None else ("%+d" % d if d else "0"))
            for f, va, vb, d in diff(a, b)]
    header = ("metric", "A", "B", "B-A")
    widths = [max(len(r[i]) for r in rows + [header]) for i in range(4)]
    out = ["# %s, %s" % (arch, COUNTING_NOTE), "# A: " + a.name, "# B: " + b.name]
    for r in [header] + rows:
        out.append(r[0].ljust(widths[0]) + "  " + "  ".join(
            c.rjust(w) for c, w in zip(r[1:], widths[1:])))
    return "\n".join(out)


def to_json(stats, binary, arch="sm_90"):
    return json.dumps({"binary": binary, "arch": arch, "counting": COUNTING_NOTE,
                       "kernels": {k: s.as_dict() for k, s in stats.items()}}, indent=2)


def main(argv=None):
    p = argparse.ArgumentParser(
        description="Per-kernel registers, spills, memory and floating-point instruction "
                    "counts read from a CUDA binary with cuobjdump (no GPU needed). "
                    + COUNTING_NOTE[0].upper() + COUNTING_NOTE[1:] + ".",
        epilog="Columns: " + " ".join(LEGEND))
    p.add_argument("binary", help="executable, object file or cubin with SASS for --arch")
    p.add_argument("--kernel", metavar="REGEX",
                   help="only kernels whose demangled or mangled name matches (re.search)")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.add_argument("--diff", nargs=2, metavar=("KERNEL_A", "KERNEL_B"),
                   help="compare two kernels (exact name, or a regex matching exactly one)")
    p.add_argument("--arch", default="sm_90", help="SASS architecture to read (default sm_90)")
    p.add_argument("--ptxas-log", metavar="FILE",
                   help="`-Xptxas -v` output of the build, for spill bytes")
    args = p.parse_args(argv)
    try:
        stats = audit(args.binary, args.arch, args.ptxas_log)
        if args.kernel:
            stats = select(stats, args.kernel)
            if not stats:
                raise AuditError("no kernel matches %r in %s" % (args.kernel, args.binary))
        if args.diff:
            a, b = (find_kernel(stats, n) for n in args.diff)
            if args.json:
                print(json.dumps({"arch": args.arch, "counting": COUNTING_NOTE,
                                  "a": a.name, "b": b.name,
                                  "diff": {f: {"a": va, "b": vb, "delta": d}
                                           for f, va, vb, d in diff(a, b)}}, indent=2))
            else:
                print(format_diff(a, b, args.arch))
        elif args.json:
            print(to_json(stats, args.binary, args.arch))
        else:
            print(format_table(stats, args.arch))
    except AuditError as e:
        print("audit: error: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
