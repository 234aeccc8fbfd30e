"""Tests for tools/audit.py on captured cuobjdump/nvdisasm/ptxas text (data/,
made from data/fixture.cu with nvcc 13.0), plus an end-to-end run on a freshly
compiled cubin when nvcc and cuobjdump are installed."""

import contextlib
import importlib.util
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from unittest import mock

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "data")
AUDIT_PY = os.path.join(HERE, "..", "..", "tools", "audit.py")

_spec = importlib.util.spec_from_file_location("gpusolve_audit", AUDIT_PY)
audit = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(audit)

TRIAD_F = "_ZN4demo5triadIfEEvPT_PKS1_S4_S4_i"
TRIAD_D = "_ZN4demo5triadIdEEvPT_PKS1_S4_S4_i"
SPILL = "_Z5spillPfPKf"
MIXED = "_Z5mixedPdPfib"
LOCAL = "_Z13local_scratchPfPKii"


def read(name):
    with open(os.path.join(DATA, name)) as f:
        return f.read()


def identity(names):
    return {n: n for n in names}


# Counts read from data/cubin_sm90.sass by eye (and cross-checked with grep):
# each kernel's "Function :" block, NOP excluded.
EXPECTED_SM90 = {
    TRIAD_F: dict(instructions=24, global_loads=3, global_stores=1, const_reads=8,
                  const_loads=8, fp32_fma=1),
    TRIAD_D: dict(instructions=24, global_loads=3, global_stores=1, const_reads=8,
                  const_loads=8, fp64_fma=1),
    SPILL: dict(instructions=80, local_loads=12, local_stores=8, global_loads=24,
                global_stores=1, const_reads=4, const_loads=4, fp32_fma=24),
    MIXED: dict(instructions=111, global_loads=4, global_stores=1, generic_loads=1,
                generic_stores=1, shared_stores=1, const_reads=7, const_loads=7,
                fp64_add=2, fp64_mul=7, fp64_fma=14, special=2, convert=2),
    LOCAL: dict(instructions=127, local_loads=2, local_stores=5, global_loads=3,
                global_stores=1, shared_loads=1, shared_stores=1, const_reads=5,
                const_loads=5, fp32_add=3, fp32_mul=11, fp32_fma=5, special=3, convert=5),
}


class ClassifyTest(unittest.TestCase):
    def test_constant_operand_and_modifiers(self):
        self.assertEqual(audit.classify("FFMA", " R2, R3, c[0x0][0x210], R4 "),
                         ["fp32_fma", "const_reads"])
        self.assertEqual(audit.classify("LDG.E.64", " R2, desc[UR4][R2.64] "), ["global_loads"])
        self.assertEqual(audit.classify("ULDC.64", " UR4, c[0x0][0x208] "),
                         ["const_loads", "const_reads"])
        self.assertEqual(audit.classify("LDGSTS.E.BYPASS.128", " [R1], desc[UR4][R2.64] "),
                         ["global_loads", "shared_stores"])
        self.assertEqual(audit.classify("IMAD.WIDE", " R2, R3, 0x4, R4 "), [])

    def test_predicated_and_braced_lines(self):
        text = ("\tcode for sm_90\n\t\tFunction : k\n"
                "        /*0000*/               @!P0 FADD.FTZ R2, R0, c[0x3][0x10] ;  /* 0x0 */\n"
                "        /*0010*/              { @UP1 MUFU.SIN R3, R0 ;\n"
                "        /*0020*/                   NOP;\n"
                "        /*0030*/               @PT STL [R1+0x4], R9 ;\n")
        (name, c), = audit.parse_sass(text)
        self.assertEqual(name, "k")
        self.assertEqual((c["instructions"], c["fp32_add"], c["const_reads"], c["special"],
                          c["local_stores"], c["op:NOP"]), (3, 1, 1, 1, 1, 0))


class ParseResUsageTest(unittest.TestCase):
    def test_cubin(self):
        res = dict(audit.parse_res_usage(read("cubin_sm90.res")))
        self.assertEqual(set(res), {TRIAD_F, TRIAD_D, SPILL, MIXED, LOCAL})
        self.assertEqual(res[TRIAD_D], dict(registers=16, stack=0, shared=0, local=0,
                                            constant={0: 564}, texture=0, surface=0, sampler=0))
        self.assertEqual(res[TRIAD_F]["registers"], 14)
        self.assertEqual((res[SPILL]["registers"], res[SPILL]["stack"]), (24, 32))
        self.assertEqual((res[MIXED]["shared"], res[MIXED]["constant"]), (1536, {0: 549}))
        self.assertEqual((res[LOCAL]["stack"], res[LOCAL]["shared"]), (256, 1280))

    def test_executable_is_filtered_by_arch(self):
        text = read("exe_sm80_sm90.res")
        sm90 = audit.parse_res_usage(text, "sm_90")
        sm80 = dict(audit.parse_res_usage(text, "sm_80"))
        self.assertEqual(sm90, audit.parse_res_usage(read("cubin_sm90.res")))
        self.assertEqual(len(sm80), 5)
        self.assertEqual((sm80[TRIAD_D]["registers"], sm80[TRIAD_D]["constant"]), (14, {0: 388}))
        self.assertEqual((sm80[SPILL]["stack"], sm80[LOCAL]["shared"]), (40, 256))
        self.assertEqual(audit.parse_res_usage(text, "sm_100"), [])


class ParseSassTest(unittest.TestCase):
    def check(self, functions):
        got = dict(functions)
        self.assertEqual([n for n, _ in functions], [TRIAD_D, TRIAD_F, SPILL, MIXED, LOCAL])
        for name, expected in EXPECTED_SM90.items():
            for field in audit.COUNT_FIELDS:
                with self.subTest(kernel=name, field=field):
                    self.assertEqual(got[name][field], expected.get(field, 0))

    def test_cuobjdump_cubin(self):
        functions = audit.parse_sass(read("cubin_sm90.sass"))
        self.check(functions)
        spill = dict(functions)[SPILL]
        self.assertEqual((spill["op:IMAD"], spill["op:LDC"], spill["op:BRA"]), (2, 3, 1))

    def test_nvdisasm_format(self):
        self.check(audit.parse_sass(read("cubin_sm90.nvdisasm")))

    def test_executable_is_filtered_by_arch(self):
        text = read("exe_sm80_sm90.sass")
        self.check(audit.parse_sass(text, "sm_90"))
        sm80 = dict(audit.parse_sass(text, "sm_80"))
        self.assertEqual(len(sm80), 5)
        self.assertEqual((sm80[TRIAD_F]["instructions"], sm80[SPILL]["local_loads"]), (19, 11))


class PtxasLogTest(unittest.TestCase):
    def test_spills(self):
        log = audit.parse_ptxas_log(read("ptxas_sm90.log"))
        self.assertEqual(len(log), 5)
        self.assertEqual(log[SPILL], dict(stack_frame=32, spill_stores=32, spill_loads=48))
        self.assertEqual(log[LOCAL], dict(stack_frame=256, spill_stores=0, spill_loads=0))

    def test_two_architectures(self):
        text = read("ptxas_sm80_sm90.log")
        sm90, sm80 = audit.parse_ptxas_log(text, "sm_90"), audit.parse_ptxas_log(text, "sm_80")
        self.assertEqual(len(sm90), 5)
        self.assertEqual(sm90[SPILL], dict(stack_frame=32, spill_stores=32, spill_loads=48))
        self.assertEqual(sm80[SPILL], dict(stack_frame=40, spill_stores=36, spill_loads=48))
        self.assertEqual(audit.parse_ptxas_log(text, "sm_100"), {})


class AuditTextTest(unittest.TestCase):
    def setUp(self):
        self.res, self.sass = read("cubin_sm90.res"), read("cubin_sm90.sass")

    def test_combines_resources_counts_and_spills(self):
        stats = audit.audit_text(self.res, self.sass, read("ptxas_sm90.log"), demangle=identity)
        s = stats[SPILL]
        self.assertIsInstance(s, audit.KernelStats)
        self.assertEqual((s.registers, s.stack, s.spill_stores, s.spill_loads), (24, 32, 32, 48))
        self.assertEqual((s.local_loads, s.local_stores, s.fp_arith), (12, 8, 24))
        self.assertEqual(stats[MIXED].fp_arith, 23)
        self.assertEqual(stats[MIXED].opcodes["DSETP"], 2)
        d = stats[LOCAL].as_dict()
        self.assertEqual((d["constant"], d["fp_arith"], d["stack"]), ({"0": 548}, 19, 256))

    def test_without_ptxas_log_spills_are_unknown(self):
        s = audit.audit_text(self.res, self.sass, demangle=identity)[SPILL]
        self.assertIsNone(s.spill_stores)
        self.assertIsNone(s.spill_loads)

    def test_function_missing_from_res_usage(self):
        s = audit.audit_text("", self.sass, demangle=identity)[TRIAD_F]
        self.assertIsNone(s.registers)
        self.assertEqual(s.global_loads, 3)

    def test_repeats_collapse_when_identical_and_are_numbered_when_not(self):
        stats = audit.audit_text(self.res * 2, self.sass * 2, demangle=identity)
        self.assertEqual(len(stats), 5)
        other = self.res.replace("REG:14 ", "REG:40 ")
        stats = audit.audit_text(self.res + other, self.sass * 2, demangle=identity)
        self.assertEqual(len(stats), 6)
        self.assertEqual((stats[TRIAD_F].registers, stats[TRIAD_F + " [2]"].registers), (14, 40))

    @unittest.skipUnless(shutil.which("c++filt") or audit.find_tool("cu++filt"),
                         "no c++filt or cu++filt to demangle with")
    def test_demangled_names(self):
        stats = audit.audit_text(self.res, self.sass)
        self.assertIn("void demo::triad<float>(float*, float const*, float const*, "
                      "float const*, int)", stats)
        self.assertIn("spill(float*, float const*)", stats)
        self.assertEqual(stats["spill(float*, float const*)"].mangled, SPILL)

    def test_select_and_find_kernel(self):
        stats = audit.audit_text(self.res, self.sass, demangle=identity)
        self.assertEqual(set(audit.select(stats, "triad")), {TRIAD_F, TRIAD_D})
        self.assertEqual(audit.find_kernel(stats, TRIAD_F).mangled, TRIAD_F)
        self.assertEqual(audit.find_kernel(stats, "spill").mangled, SPILL)
        with self.assertRaisesRegex(audit.AuditError, "matches 2 kernels"):
            audit.find_kernel(stats, "triad")
        with self.assertRaisesRegex(audit.AuditError, "matches no kernels"):
            audit.find_kernel(stats, "nothing")


class FormatTest(unittest.TestCase):
    def setUp(self):
        self.stats = audit.audit_text(read("cubin_sm90.res"), read("cubin_sm90.sass"),
                                      read("ptxas_sm90.log"), demangle=identity)

    def test_table(self):
        lines = audit.format_table(self.stats).splitlines()
        self.assertIn("static counts", lines[0])
        header = next(l for l in lines if not l.startswith("#"))
        rows = lines[lines.index(header) + 1:]
        self.assertEqual(len(rows), 5)
        cols = header.split()
        spill = dict(zip(cols, next(r for r in rows if r.endswith(SPILL)).split()))
        self.assertEqual((spill["Regs"], spill["Stack"], spill["Spill"], spill["LDL"],
                          spill["STL"], spill["LDG"], spill["Ffma"], spill["Kernel"]),
                         ("24", "32", "32/48", "12", "8", "24", "24", SPILL))
        # Numbers are right-aligned: every column ends at the same offset.
        end = header.index("Insts") + len("Insts")
        self.assertTrue(all(r[end - 1].isdigit() and r[end] == " " for r in rows))

    def test_diff(self):
        rows = {f: (a, b, d) for f, a, b, d in
                audit.diff(self.stats[TRIAD_F], self.stats[MIXED])}
        self.assertEqual(rows["registers"], (14, 24, 10))
        self.assertEqual(rows["global_loads"], (3, 4, 1))
        self.assertEqual(rows["fp_arith"], (1, 23, 22))
        self.assertEqual(rows["const_reads"], (8, 7, -1))
        text = audit.format_diff(self.stats[TRIAD_F], self.stats[MIXED])
        self.assertRegex(text, r"\nregisters\s+14\s+24\s+\+10\n")
        self.assertRegex(text, r"\nconst_reads\s+8\s+7\s+-1\n")
        self.assertRegex(text, r"\nstack\s+0\s+0\s+0\n")

    def test_json(self):
        doc = json.loads(audit.to_json(self.stats, "x.cubin"))
        self.assertEqual((doc["binary"], doc["arch"]), ("x.cubin", "sm_90"))
        k = doc["kernels"][LOCAL]
        self.assertEqual((k["registers"], k["local_loads"], k["local_stores"], k["fp_arith"],
                          k["opcodes"]["I2FP"]), (24, 2, 5, 19, 5))


FAKE_CUOBJDUMP = """#!{python}
# Stands in for cuobjdump: prints captured output for -res-usage / -sass.
import sys
data = {data!r}
if not sys.argv[-1].endswith(".cubin"):
    sys.stderr.write("cuobjdump fatal   : Could not open input file\\n")
    sys.exit(1)
name = "cubin_sm90.res" if "-res-usage" in sys.argv else "cubin_sm90.sass"
sys.stdout.write(open(data + "/" + name).read())
"""


class CommandLineTest(unittest.TestCase):
    """main() end to end, with a stand-in cuobjdump that prints the fixtures."""

    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.tmp)
        tool = os.path.join(self.tmp, "cuobjdump")
        with open(tool, "w") as f:
            f.write(FAKE_CUOBJDUMP.format(python=sys.executable, data=DATA))
        os.chmod(tool, 0o755)
        self.binary = os.path.join(self.tmp, "k.cubin")
        open(self.binary, "w").close()
        patcher = mock.patch.dict(os.environ, {"CUOBJDUMP": tool})
        patcher.start()
        self.addCleanup(patcher.stop)

    def run_main(self, *argv):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = audit.main(list(argv))
        return rc, out.getvalue(), err.getvalue()

    def test_table_with_kernel_filter(self):
        rc, out, _ = self.run_main(self.binary, "--kernel", "triad")
        self.assertEqual(rc, 0)
        rows = [l for l in out.splitlines() if "triad" in l]
        self.assertEqual(len(rows), 2)

    def test_json(self):
        rc, out, _ = self.run_main(self.binary, "--json", "--kernel", "^spill")
        self.assertEqual(rc, 0)
        kernels = json.loads(out)["kernels"]
        self.assertEqual(len(kernels), 1)
        (k,) = kernels.values()
        self.assertEqual((k["stack"], k["local_loads"], k["spill_stores"]), (32, 12, None))

    def test_diff_with_ptxas_log(self):
        rc, out, _ = self.run_main(self.binary, "--diff", "triadIf", "^spill",
                                   "--ptxas-log", os.path.join(DATA, "ptxas_sm90.log"))
        self.assertEqual(rc, 0)
        self.assertRegex(out, r"\nspill_loads\s+0\s+48\s+\+48\n")
        self.assertRegex(out, r"\nlocal_stores\s+0\s+8\s+\+8\n")

    def test_errors(self):
        rc, _, err = self.run_main(self.binary, "--kernel", "no_such_kernel")
        self.assertEqual((rc, "no kernel matches" in err), (1, True))
        rc, _, err = self.run_main(os.path.join(self.tmp, "absent.cubin"))
        self.assertEqual((rc, "no such file" in err), (1, True))
        other = os.path.join(self.tmp, "k.bin")
        open(other, "w").close()
        rc, _, err = self.run_main(other)
        self.assertEqual((rc, "Could not open input file" in err), (1, True))
        rc, _, err = self.run_main(self.binary, "--diff", "triad", "spill")
        self.assertEqual((rc, "matches 2 kernels" in err), (1, True))
        rc, _, err = self.run_main(self.binary, "--arch", "sm_80")
        self.assertEqual((rc, "holds no sm_80 machine code" in err), (1, True))

    def test_missing_cuobjdump(self):
        with mock.patch.dict(os.environ, {"CUOBJDUMP": os.path.join(self.tmp, "nope")}):
            rc, _, err = self.run_main(self.binary)
        self.assertEqual((rc, "cuobjdump not found" in err), (1, True))


NVCC = shutil.which("nvcc") or ("/usr/local/cuda/bin/nvcc"
                                if os.access("/usr/local/cuda/bin/nvcc", os.X_OK) else None)


@unittest.skipUnless(NVCC, "nvcc not found: end-to-end audit of a fresh cubin skipped")
@unittest.skipUnless(audit.find_tool("cuobjdump", "CUOBJDUMP"),
                     "cuobjdump not found (pip install nvidia-cuda-cuobjdump "
                     "nvidia-cuda-nvdisasm): end-to-end audit skipped")
class EndToEndTest(unittest.TestCase):
    def test_fresh_cubin(self):
        with tempfile.TemporaryDirectory() as tmp:
            cubin = os.path.join(tmp, "fixture.cubin")
            log = os.path.join(tmp, "ptxas.log")
            proc = subprocess.run([NVCC, "-arch=sm_90", "-cubin", "-Xptxas", "-v", "-o", cubin,
                                   os.path.join(DATA, "fixture.cu")],
                                  capture_output=True, text=True)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            with open(log, "w") as f:
                f.write(proc.stderr + proc.stdout)
            stats = {s.mangled: s for s in audit.audit(cubin, ptxas_log=log).values()}
            # Facts that follow from the source whatever the compiler version.
            self.assertEqual(set(stats), {TRIAD_F, TRIAD_D, SPILL, MIXED, LOCAL})
            for name, fma in ((TRIAD_F, "fp32_fma"), (TRIAD_D, "fp64_fma")):
                s = stats[name]
                self.assertEqual((s.global_loads, s.global_stores, getattr(s, fma),
                                  s.local_loads + s.local_stores), (3, 1, 1, 0))
            local = stats[LOCAL]
            self.assertEqual(local.stack, 256)
            self.assertGreater(local.local_loads, 0)
            self.assertGreater(local.local_stores, 0)
            self.assertGreater(stats[SPILL].spill_stores, 0)
            self.assertGreater(stats[MIXED].generic_loads, 0)
            self.assertGreater(stats[MIXED].generic_stores, 0)
            rc = subprocess.run([sys.executable, AUDIT_PY, cubin, "--kernel", "triad"],
                                capture_output=True, text=True)
            self.assertEqual(rc.returncode, 0, rc.stderr)
            self.assertEqual(sum("triad" in l for l in rc.stdout.splitlines()), 2)


if __name__ == "__main__":
    unittest.main()
