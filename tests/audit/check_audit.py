#!/usr/bin/env python3
"""Holds the claims of tests/audit/RESULTS.md against the compiled audit kernels.

Reads the sm_90 cubin built from audit_kernels.cu with tools/audit.py (no GPU)
and checks what was measured with nvcc 13.0: the thesis's vector triad
(Table 4) and contact-point expression of Eq. (9) (Table 5) in their plain C++,
expression-template (ET) and cached variants, and one body with its descriptors
passed by value, as a __grid_constant__ parameter and through
ConstantDeviceMemory. Exits 1 naming kernel and metric when a claim fails.

    python3 tests/audit/check_audit.py CUBIN [--markdown] [--ptxas-log FILE]

--markdown prints the table of RESULTS.md (ours beside thesis Tables 4 and 5).
"""

import argparse
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import audit  # noqa: E402  (tools/audit.py, by path)

TYPES = ("float", "double")
# sm_90 has 65536 registers per SM for at most 2048 resident threads: a kernel
# with at most this many registers per thread is never limited by them.
FULL_OCCUPANCY_REGISTERS = 32


def kernel_regex(body, t, launcher="each_element"):
    """Regex for the demangled name of launcher<body<t>>."""
    if launcher == "constant":
        return r"each_element<gpusolve_audit::FromConstant<gpusolve_audit::%s<%s>," % (body, t)
    return r"gpusolve_audit::%s<gpusolve_audit::%s<%s>\s*>\(" % (launcher, body, t)


# label -> (body, how the descriptors reach the kernel, description)
VARIANTS = {
    "triad_plain": ("TriadPlain", "each_element", "triad, plain C++"),
    "triad_et": ("TriadET", "each_element", "triad, ET (Global)"),
    "contact_plain": ("ContactPlain", "each_element", "Eq. (9), plain C++"),
    "contact_et": ("ContactET", "each_element", "Eq. (9), ET (Global)"),
    "contact_cached": ("ContactCached", "each_element", "Eq. (9), ET (cached)"),
    "contact_write_through": ("ContactETWriteThrough", "each_element",
                              "Eq. (9), ET (Global), thesis write-through"),
    "triad_et_grid_constant": ("TriadET", "each_element_grid_constant",
                               "triad ET, __grid_constant__ param"),
    "triad_et_constant": ("TriadET", "constant", "triad ET, ConstantDeviceMemory"),
    "contact_cached_grid_constant": ("ContactCached", "each_element_grid_constant",
                                     "Eq. (9) cached, __grid_constant__ param"),
    "contact_cached_constant": ("ContactCached", "constant",
                                "Eq. (9) cached, ConstantDeviceMemory"),
}

# Thesis Tables 4 and 5 (G80, decuda): registers, global loads, stores,
# constant memory loads, flops. Facts quoted for comparison.
THESIS = {
    ("triad_plain", "float"): (9, 7, 3, 16, 3), ("triad_et", "float"): (6, 7, 3, 14, 3),
    ("triad_plain", "double"): (15, 7, 3, 16, 3), ("triad_et", "double"): (10, 7, 3, 14, 3),
    ("contact_plain", "float"): (14, 12, 3, 28, 13), ("contact_et", "float"): (13, 21, 3, 21, 15),
    ("contact_cached", "float"): (11, 12, 3, 21, 13),
    ("contact_plain", "double"): (25, 12, 3, 28, 15), ("contact_et", "double"): (21, 21, 3, 21, 15),
    ("contact_cached", "double"): (21, 12, 3, 21, 15),
}

# Registers measured with nvcc 13.0 (V13.0.88) for sm_90: upper bounds, so a
# compiler or library change that costs registers fails; one that saves some
# passes with a note to lower the bound.
MEASURED_REGISTERS = {
    ("triad_plain", "float"): 20, ("triad_et", "float"): 21,
    ("triad_plain", "double"): 22, ("triad_et", "double"): 28,
    ("contact_plain", "float"): 26, ("contact_et", "float"): 28,
    ("contact_cached", "float"): 28, ("contact_write_through", "float"): 32,
    ("contact_plain", "double"): 32, ("contact_et", "double"): 32,
    ("contact_cached", "double"): 32, ("contact_write_through", "double"): 31,
}


# --- the SASS in order (the audit's counts are unordered) --------------------
_CONST_OPERAND_RE = re.compile(r"\bc\[0x([0-9a-f]+)\]\[0x([0-9a-f]+)\]")
PARAM_BASE = 0x210  # sm_90: kernel parameters start here in constant bank 0
USER_CONSTANT_BANK = 3  # sm_90: __constant__ variables


def loads_after_first_store(insns):
    """Global loads issued after the kernel's first global store: the thesis's
    write-through interleaving (Listing 10) versus all loads first (Listing 9)."""
    ops = [op for op, _ in insns]
    if "STG" not in ops:
        return 0
    return ops[ops.index("STG"):].count("LDG")


def descriptor_reads(insns):
    """(reads of kernel parameters, reads of __constant__ variables): the
    instructions that read a descriptor, whichever way it was passed."""
    param = user = 0
    for _, operands in insns:
        for bank, offset in _CONST_OPERAND_RE.findall(operands):
            bank, offset = int(bank, 16), int(offset, 16)
            if bank == 0 and offset >= PARAM_BASE:
                param += 1
            elif bank == USER_CONSTANT_BANK:
                user += 1
    return param, user


# --- claims -----------------------------------------------------------------
class Checker:
    def __init__(self, stats, listing):
        self.stats, self.listing, self.failures, self.passed = stats, listing, [], 0

    def kernel(self, label, t):
        body, launcher, _ = VARIANTS[label]
        return audit.find_kernel(self.stats, kernel_regex(body, t, launcher))

    def insns(self, label, t):
        return self.listing[self.kernel(label, t).mangled]

    def expect(self, ok, label, t, metric, message):
        if ok:
            self.passed += 1
        else:
            self.failures.append("%s<%s> [%s]: %s" % (label, t, metric, message))

    def equal(self, label, t, metric, got, want, why):
        self.expect(got == want, label, t, metric, "%s, want %s (%s)" % (got, want, why))


def fp_profile(s):
    return (s.fp32_add + s.fp64_add, s.fp32_mul + s.fp64_mul, s.fp32_fma + s.fp64_fma)


def check(stats, listing):
    c = Checker(stats, listing)
    for t in TYPES:
        k = {label: c.kernel(label, t) for label in VARIANTS}

        for label, s in k.items():
            # No spills, no local memory: spilled values would be LDL/STL.
            for metric in ("local_loads", "local_stores", "stack", "local"):
                c.equal(label, t, metric, getattr(s, metric), 0, "no variant spills")
            if s.spill_stores is not None:
                c.equal(label, t, "spill bytes", s.spill_stores + s.spill_loads, 0, "no spills")
            c.expect(s.registers <= FULL_OCCUPANCY_REGISTERS, label, t, "registers",
                     "%d > %d: registers now limit occupancy on sm_90"
                     % (s.registers, FULL_OCCUPANCY_REGISTERS))
            bound = MEASURED_REGISTERS.get((label, t))
            if bound is not None:
                c.expect(s.registers <= bound, label, t, "registers",
                         "%d, measured %d with nvcc 13.0" % (s.registers, bound))
                if s.registers < bound:
                    print("note: %s<%s> uses %d registers, below the bound %d: lower it"
                          % (label, t, s.registers, bound))

        # Triad: 3 + 3 + 1 loads and 3 stores are the minimum; ET reaches it.
        for label in ("triad_plain", "triad_et"):
            c.equal(label, t, "global loads", k[label].global_loads, 7, "b, d and c once each")
            c.equal(label, t, "global stores", k[label].global_stores, 3, "a once")
            c.equal(label, t, "fp (add, mul, fma)", fp_profile(k[label]), (0, 0, 3), "3 fused mads")
        c.expect(k["triad_et"].const_reads <= k["triad_plain"].const_reads, "triad_et", t,
                 "constant reads", "%d > plain's %d"
                 % (k["triad_et"].const_reads, k["triad_plain"].const_reads))
        # Write-through interleaves stores with loads (thesis Listing 10);
        # plain C++ loads everything first (Listing 9).
        c.expect(loads_after_first_store(c.insns("triad_et", t)) > 0, "triad_et", t,
                 "loads after first store", "0: ET no longer writes through")
        c.equal("triad_plain", t, "loads after first store",
                loads_after_first_store(c.insns("triad_plain", t)), 0, "plain stores last")

        # Eq. (9): q, v, r, w once each is 12 loads. Global-only ET reaches it
        # because assign() evaluates the cross product into a temporary, so no
        # store can alias a later load; written through, it takes the thesis's 21.
        for label in ("contact_plain", "contact_et", "contact_cached"):
            c.equal(label, t, "global loads", k[label].global_loads, 12, "q, v, r, w once each")
            c.equal(label, t, "global stores", k[label].global_stores, 3, "p once")
            c.equal(label, t, "loads after first store",
                    loads_after_first_store(c.insns(label, t)), 0, "evaluated before stored")
        c.equal("contact_write_through", t, "global loads",
                k["contact_write_through"].global_loads, 21, "thesis Table 5, ET row")
        want_fp = fp_profile(k["contact_plain"])
        c.equal("contact_plain", t, "fp (add, mul, fma)", want_fp, (3, 3, 9), "measured")
        for label in ("contact_et", "contact_cached", "contact_write_through"):
            c.equal(label, t, "fp (add, mul, fma)", fp_profile(k[label]), want_fp, "same as plain")
        for label in ("contact_et", "contact_cached"):
            c.expect(k[label].const_reads < k["contact_plain"].const_reads, label, t,
                     "constant reads", "%d, not below plain's %d"
                     % (k[label].const_reads, k["contact_plain"].const_reads))
        # Caching r and w is free but no longer needed.
        c.expect(k["contact_cached"].registers <= k["contact_et"].registers, "contact_cached", t,
                 "registers", "%d > ET's %d" % (k["contact_cached"].registers,
                                               k["contact_et"].registers))

        # Descriptors by value, as __grid_constant__ and in ConstantDeviceMemory:
        # the same code, reading the same number of descriptor words from bank 0
        # (parameters) or bank 3 (__constant__).
        for body in ("triad_et", "contact_cached"):
            base = k[body]
            base_param, base_user = descriptor_reads(c.insns(body, t))
            c.equal(body, t, "__constant__ reads", base_user, 0, "passed by value")
            for way in ("grid_constant", "constant"):
                label = body + "_" + way
                other = k[label]
                c.equal(label, t, "registers", other.registers, base.registers, "same as by value")
                c.equal(label, t, "opcodes", other.opcodes, base.opcodes, "same code as by value")
                param, user = descriptor_reads(c.insns(label, t))
                want = (base_param, 0) if way == "grid_constant" else (0, base_param)
                c.equal(label, t, "descriptor reads (param, __constant__)", (param, user), want,
                        "bank 0 parameters vs bank 3")
    return c


# --- report -----------------------------------------------------------------
def markdown(stats, listing):
    header = ("| Type | Variant | Registers | Global Loads/Stores | Loads after 1st store "
              "| Constant reads (descriptor) | Flops (add/mul/fma) | Instructions "
              "| Thesis: Registers | Thesis: Loads/Stores | Thesis: Constant | Thesis: Flops |")
    rows = [header, "|" + "|".join("---" for _ in range(header.count("|") - 1)) + "|"]
    for t in TYPES:
        for label, (body, launcher, description) in VARIANTS.items():
            s = audit.find_kernel(stats, kernel_regex(body, t, launcher))
            insns = listing[s.mangled]
            param, user = descriptor_reads(insns)
            th = THESIS.get((label, t))
            thesis = ("%d | %d / %d | %d | %d" % th) if th else "- | - | - | -"
            rows.append("| %s | %s | %d | %d / %d | %d | %d (%d) | %d (%d/%d/%d) | %d | %s |" % (
                t, description, s.registers, s.global_loads, s.global_stores,
                loads_after_first_store(insns), s.const_reads, param + user,
                s.fp_arith, *fp_profile(s), s.instructions, thesis))
    return "\n".join(rows)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("binary", help="cubin (or object) built from tests/audit/audit_kernels.cu")
    p.add_argument("--markdown", action="store_true", help="print the results table")
    p.add_argument("--ptxas-log", metavar="FILE", help="`-Xptxas -v` output, for spill bytes")
    p.add_argument("--arch", default="sm_90")
    args = p.parse_args(argv)
    try:
        stats = audit.audit(args.binary, args.arch, args.ptxas_log)
        listing = audit.sass_listing(args.binary, args.arch)
        if args.markdown:
            print(markdown(stats, listing))
        c = check(stats, listing)
    except audit.AuditError as e:
        print("check_audit: error: %s" % e, file=sys.stderr)
        return 1
    for f in c.failures:
        print("FAIL %s" % f, file=sys.stderr)
    print("check_audit: %d claims hold, %d fail (%s, %s)"
          % (c.passed, len(c.failures), args.arch, os.path.basename(args.binary)))
    return 1 if c.failures else 0


if __name__ == "__main__":
    sys.exit(main())
