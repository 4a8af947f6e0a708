#!/usr/bin/env python3
"""Where a measured cost goes, by render stage, and what it costs in cycles.

    profile.py ELF WITH.log WITHOUT.log DIV --core m0plus|m4

WITH.log and WITHOUT.log are `-d plugin` logs of the qemu-insn plugin run
with `each=on` (tests/mcu/qemu-insn.c): one `at VADDR COUNT` line per guest
instruction address. The cost is (WITH - WITHOUT) / DIV per instruction
address, as the rest of tests/mcu/run measures it (for example 20 frames
minus 0 frames over 20).

Stages. Each instruction's inline chain (addr2line -i: innermost frame
first, out to the function it was compiled into) is searched innermost
first for the first frame that names a stage (STAGES below); a helper
(a fixed-point product, a dot product) thus counts in the stage that
inlined it. An out-of-line function that names no stage of its own (a
compiler-builtins division, memset, an outlined helper) is charged to its
callers in proportion to the executions of each direct call site (`bl`,
or a tail `b` into it), like gprof's call-graph split: it assumes every
call costs the same. Cost no chain or call site places is `other`.

Cycles. Each executed instruction is priced by the core's published
timing (zero wait states): ARM Cortex-M0+ TRM (DDI 0484C) table 3.1 with
the single-cycle multiplier (RP2040 has it), and ARM Cortex-M4 TRM
(DDI 0439B) tables 3-1 and 7-1. A conditional branch's taken count is
its executions minus those of its fall-through, where the fall-through
address's own count is reduced by the direct branches into it; `low`
and `high` bound what the model does not know: on the Cortex-M4 the
pipeline refill P of a taken branch (1 to 3 cycles) and whether a load
pipelines with the load or store before it; on the Cortex-M0+ nothing
is unknown to the model, so the two are equal. Instruction fetch from
slow flash (wait states, an XIP cache miss) is not modelled.

Prints `stage NAME VALUE` for every stage in STAGES order, `total VALUE`
and `cycles LOW HIGH`, values per DIV. `profile.py --self-test` checks the
branch and cycle model on hand-counted code (tests/mcu/run runs it).
"""
import argparse
import re
import subprocess
import sys
from collections import defaultdict

# (stage, regular expression on a demangled frame's function name). A frame
# names a stage when it matches; `pixels` frames count as pixels only
# inside a triangle fill (`fill_small_triangle`, `fill_polygon`; outside
# them, the same fills are a clear). The names are today's: `tests/mcu/run`
# fails when `other` grows past a few per cent of a frame, which is what a
# rename that leaves a rule behind looks like.
STAGES = [
    ("clear", r"Target>::fill_solid$|fill_unrolled$|Target>::clear$|Band<C>::clear(::\{\{closure\}\})?$|DepthBuffer<K>::clear(::\{\{closure\}\})?$|raster::depth::fill_far_words$"),
    ("vertices", r"Renderer<S>::project(::\{\{closure\}\})?$|::project_vertex$|::project_vertices$|Projection<S>::project$|Pipeline<S>::project$"),
    ("lighting", r"(Prepared|Normal)Light<S>::intensity$|PreparedLight<S>::shade$|quantize_intensity$|ScalableColor>::scale$"),
    ("dispatch", r"scene::render::Tri<S,_>::draw(::\{\{closure\}\})?$|scene::render::Frame<S>::draw(_with|_unclipped)?(::\{\{closure\}\})?$|scene::render::misses_rows$"),
    ("culling", r"Pipeline<S>>?::keep_inside$|Pipeline<S>>?::keep$"),
    ("clipping", r"::project_polygon$|sightline::pipeline::clip::"),
    ("set-up", r"Gradient::new(::\{\{closure\}\})?$|AreaRecip::new$|EdgeStepper(32)?::new$|raster::edge::first_center$|raster::gradient::cross(::\{\{closure\}\})?$|sightline::raster::area2$"),
    ("edges", r"sightline::raster::(fill_polygon|fill_small_triangle|fill)(::\{\{closure\}\})?$|sightline::raster::chain_row$|EdgeStepper(32)?::step$"),
    ("spans", r"Gradient::span(_with|_tiny)?$"),
    ("pixels", r"sightline::raster::depth::|DepthTest>::test_(write|fill)$|Layout::span_exact$|::span_mut$|::exact_span_mut$|::clipped_span_mut$|SpanShader<.*>::span$|raster::texture::"),
]
ORDER = [s for s, _ in STAGES] + ["other"]
RULES = [(s, re.compile(r)) for s, r in STAGES]
PIXEL_FILLS = re.compile(r"Target>::fill_solid$|fill_unrolled$|sightline::target::framebuffer::fill_run(::\w+)?$|sightline::raster::depth::fill_words$")
TRIANGLE_FILLS = re.compile(r"sightline::raster::(fill_polygon|fill_small_triangle)$")


def load(path):
    counts = {}
    with open(path) as f:
        for line in f:
            if line.startswith("at "):
                _, a, c = line.split()
                counts[int(a, 16)] = int(c)
            elif line.startswith("error:"):
                sys.exit(f"{path}: {line.strip()}")
    if not counts:
        sys.exit(f"{path}: no `at` lines (was the plugin run with each=on?)")
    return counts


def disassemble(elf):
    """Instruction address -> (mnemonic, operands, size), function symbol
    starts, and direct branch targets (address -> target)."""
    out = subprocess.run(
        ["llvm-objdump", "-d", "--no-show-raw-insn", "--section=.text", elf],
        capture_output=True, text=True, check=True).stdout
    insns, funcs = {}, []
    order = []
    sym = re.compile(r"^([0-9a-f]+) <(.*)>:$")
    ins = re.compile(r"^ *([0-9a-f]+):\s+(\S+)\s*(.*)$")
    for line in out.splitlines():
        m = sym.match(line)
        if m:
            if not m.group(2).startswith("$"):
                funcs.append((int(m.group(1), 16), m.group(2)))
            continue
        m = ins.match(line)
        if m:
            a = int(m.group(1), 16)
            order.append(a)
            insns[a] = [m.group(2), m.group(3).split("@")[0].strip(), 0]
    for a, b in zip(order, order[1:]):
        insns[a][2] = b - a
    if order:
        insns[order[-1]][2] = 2
    return insns, sorted(funcs)


def chains(elf, addrs):
    out = subprocess.run(
        ["addr2line", "-a", "-f", "-i", "-C", "-e", elf] + [hex(a) for a in addrs],
        capture_output=True, text=True, check=True).stdout.splitlines()
    result, cur, i = {}, None, 0
    while i < len(out):
        if out[i].startswith("0x"):
            cur = int(out[i], 16)
            result[cur] = []
            i += 1
        else:
            result[cur].append(out[i])
            i += 2
    return result


def stage_of(chain):
    inside_fill = any(TRIANGLE_FILLS.search(f) for f in chain)
    for f in chain:
        if PIXEL_FILLS.search(f):
            if inside_fill:
                return "pixels"
            continue
        for s, r in RULES:
            if r.search(f):
                return s
    return None


BRANCH = re.compile(r"^(b|bl|blx|bx|cbz|cbnz)(eq|ne|cs|hs|cc|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le|al)?(\.[nw])?$")
TARGET = re.compile(r"^(?:r\d+, )?0x([0-9a-f]+)")


def branch_info(mn, ops):
    """(kind, target): kind is 'cond', 'jump', 'call', 'indirect', or None."""
    m = BRANCH.match(mn)
    if not m:
        if mn.startswith("pop") and "pc" in ops:
            return "indirect", None
        if mn in ("mov", "add") and ops.startswith("pc"):
            return "indirect", None
        return None, None
    base, cond = m.group(1), m.group(2)
    t = TARGET.match(ops)
    target = int(t.group(1), 16) if t else None
    if base in ("bx", "blx") and target is None:
        return "indirect", None
    if base == "bl":
        return "call", target
    if base in ("cbz", "cbnz") or (cond and cond != "al"):
        return "cond", target
    return "jump", target


def taken_counts(insns, cost):
    """Executions of every branch that jumped (conditional: executions
    minus fall-through; the fall-through address's count less the direct
    branches into it)."""
    into = defaultdict(list)
    kinds = {}
    for a, (mn, ops, _) in insns.items():
        if a not in cost:
            continue
        k, t = branch_info(mn, ops)
        if k:
            kinds[a] = (k, t)
            if t is not None and k in ("cond", "jump"):
                into[t].append(a)
    taken = {a: (cost[a] if k in ("jump", "call", "indirect") else 0.0) for a, (k, _) in kinds.items()}
    for _ in range(8):
        changed = False
        for a, (k, _) in kinds.items():
            if k != "cond":
                continue
            nxt = a + insns[a][2]
            arrivals = sum(taken[b] for b in into.get(nxt, []) if b != a)
            fall = max(0.0, min(cost[a], cost.get(nxt, 0.0) - arrivals))
            v = cost[a] - fall
            if abs(v - taken[a]) > 1e-9:
                taken[a] = v
                changed = True
        if not changed:
            break
    return kinds, taken


def regs(ops):
    m = re.search(r"\{(.*)\}", ops)
    if not m:
        return 1
    n = 0
    for part in m.group(1).split(","):
        part = part.strip()
        r = re.match(r"[rsd](\d+)-[rsd](\d+)", part)
        n += int(r.group(2)) - int(r.group(1)) + 1 if r else 1
    return n


LOADSTORE = re.compile(r"^(ldr|str)(b|h|sb|sh|d)?(\.[nw])?$")


def price(core, insns, cost, kinds, taken):
    lo = hi = 0.0
    for a, n in cost.items():
        mn, ops, size = insns.get(a, ("?", "", 2))
        k, _ = kinds.get(a, (None, None))
        t = taken.get(a, 0.0)
        if core == "m0plus":
            if k == "call" and mn == "bl":
                c = 3 * n
            elif k in ("cond", "jump"):
                c = n + t
            elif k == "indirect":
                # POP {loreglist, PC}: 3 + N, N counting the low registers.
                c = (3 + regs(ops) - 1) * n if mn.startswith("pop") else 2 * n
            elif mn in ("push", "pop", "ldm", "stm", "ldmia", "stmia"):
                c = (1 + regs(ops)) * n
            elif LOADSTORE.match(mn):
                c = 2 * n
            else:
                c = n
            lo += c
            hi += c
        else:  # Cortex-M4F
            prev = insns.get(a - 2) or insns.get(a - 4)
            if k in ("call", "jump", "indirect", "cond"):
                extra_regs = regs(ops) if mn.startswith("pop") else 0
                base = n + extra_regs * n
                lo += base + 1 * t
                hi += base + 3 * t
                continue
            if mn in ("push", "pop", "ldm", "stm", "ldmia", "stmia", "ldmdb", "stmdb",
                      "vpush", "vpop", "vldmia", "vstmia", "vldmdb", "vstmdb"):
                c = (1 + regs(ops)) * n
                lo += c
                hi += c
                continue
            if LOADSTORE.match(mn) or mn in ("vldr", "vstr"):
                # N adjacent single loads/stores take N + 1 cycles.
                pipelined = prev is not None and (LOADSTORE.match(prev[0]) or prev[0] in ("vldr", "vstr"))
                lo += (1 if pipelined else 2) * n
                hi += 2 * n
                continue
            if mn in ("sdiv", "udiv"):
                lo += 2 * n
                hi += 12 * n
                continue
            if re.match(r"^v(div|sqrt)\.f32$", mn):
                c = 14 * n
            elif re.match(r"^v(n?ml[as]|fm[as]|fnm[as])\.f32$", mn):
                c = 3 * n
            else:  # ALU, and every multiply (MUL, MLA, UMULL, ... one cycle)
                c = n
            lo += c
            hi += c
    return lo, hi


def self_test():
    """The cycle model on a hand-counted loop: `movs r0, #10`, then ten
    times `subs r0, #1; bne` (taken nine times), then `bx lr`. Cortex-M0+:
    1 + 10 + (10 + 9) + 2 = 32 cycles. Cortex-M4: 1 + 10 + 10 + 9·P + 1 + P
    with P from 1 to 3: 32 to 52. A branch entered from elsewhere: `cmp`
    at 0x10 runs 5 times, `beq 0x16` falls through to 0x14 (`movs`) which
    runs 3 times, but 0x14 is also the target of a `b` at 0x20 taken
    twice, so `beq` fell through once and was taken 4 times."""
    insns = {0x0: ["movs", "r0, #10", 2], 0x2: ["subs", "r0, #1", 2], 0x4: ["bne", "0x2 <f+0x2>", 2],
             0x6: ["bx", "lr", 2]}
    cost = {0x0: 1.0, 0x2: 10.0, 0x4: 10.0, 0x6: 1.0}
    kinds, taken = taken_counts(insns, cost)
    got = [taken[0x4], price("m0plus", insns, cost, kinds, taken), price("m4", insns, cost, kinds, taken)]
    want = [9.0, (32.0, 32.0), (32.0, 52.0)]
    insns2 = {0x10: ["cmp", "r0, #0", 2], 0x12: ["beq", "0x16 <g+0x6>", 2], 0x14: ["movs", "r1, #0", 2],
              0x16: ["movs", "r2, #0", 2], 0x20: ["b", "0x14 <g+0x4>", 2]}
    cost2 = {0x10: 5.0, 0x12: 5.0, 0x14: 3.0, 0x16: 5.0, 0x20: 2.0}
    _, taken2 = taken_counts(insns2, cost2)
    got.append(taken2[0x12])
    want.append(4.0)
    if got != want:
        sys.exit(f"profile.py self-test FAILED: got {got}, want {want}")
    print("profile.py self-test ok")


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("elf")
    ap.add_argument("with_log")
    ap.add_argument("without_log")
    ap.add_argument("div", type=float)
    ap.add_argument("--core", choices=["m0plus", "m4"], required=True)
    ap.add_argument("--unplaced", type=int, default=0,
                    help="also print the N costliest chains that named no stage")
    a = ap.parse_args()

    w, wo = load(a.with_log), load(a.without_log)
    cost = {k: (w.get(k, 0) - wo.get(k, 0)) / a.div for k in set(w) | set(wo)}
    cost = {k: v for k, v in cost.items() if v != 0}
    # A few addresses may run less in the longer run (printing "20" takes
    # other digit steps than "0"); they stay in, negative, so the stages
    # sum to the measured difference.
    insns, funcs = disassemble(a.elf)
    starts = [f for f, _ in funcs]

    def func_of(addr):
        lo, hi = 0, len(starts) - 1
        if not starts or addr < starts[0]:
            return None
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if starts[mid] <= addr:
                lo = mid
            else:
                hi = mid - 1
        return starts[lo]

    ch = chains(a.elf, sorted(cost))
    stage = {addr: stage_of(ch.get(addr, [])) for addr in cost}
    totals = defaultdict(float)
    pending = defaultdict(float)  # per function: cost no frame placed
    for addr, v in cost.items():
        if stage[addr]:
            totals[stage[addr]] += v
        else:
            pending[func_of(addr)] += v

    kinds, taken = taken_counts(insns, cost)
    # Direct call sites of every function (a `bl`, or a `b` into another
    # function: a tail call), weighted by their executions.
    sites = defaultdict(list)
    for addr, (k, t) in kinds.items():
        if t is None or k not in ("call", "jump", "cond"):
            continue
        f = func_of(t)
        if f is None or f != t or f == func_of(addr):
            continue
        weight = cost[addr] if k == "call" else taken[addr]
        if weight > 0:
            sites[f].append((addr, weight))
    unplaced = defaultdict(float)
    for _ in range(64):
        moved = False
        for f in list(pending):
            v = pending.pop(f)
            if v == 0:
                continue
            total_w = sum(wt for _, wt in sites.get(f, []))
            if total_w == 0:
                totals["other"] += v
                unplaced[f] += v
                continue
            for addr, wt in sites[f]:
                share = v * wt / total_w
                if stage[addr]:
                    totals[stage[addr]] += share
                else:
                    pending[func_of(addr)] += share
            moved = True
        if not moved:
            break
    for f, v in pending.items():
        totals["other"] += v
        unplaced[f] += v

    for s in ORDER:
        print(f"stage {s} {totals[s]:.0f}")
    print(f"total {sum(cost.values()):.0f}")
    lo, hi = price(a.core, insns, cost, kinds, taken)
    print(f"cycles {lo:.0f} {hi:.0f}")
    if a.unplaced:
        names = dict(funcs)
        for f, v in sorted(unplaced.items(), key=lambda x: -x[1])[: a.unplaced]:
            print(f"unplaced {v:.0f} {names.get(f, '?')}", file=sys.stderr)


if __name__ == "__main__":
    main()
