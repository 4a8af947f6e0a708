#!/usr/bin/env bash
# sightline's share of .text by inline chain: a byte counts when any frame
# of its inlining chain (innermost first, out to the function it was
# compiled into) is code written under SRC, so sightline's own arithmetic
# inlined from Rust's core library counts too, while a compiler-builtins
# routine it calls does not. share.awk charges each byte to its innermost
# source line instead.
#   share-chain.sh ELF SRC   prints the byte count
set -euo pipefail
elf="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
# Instruction (and literal-pool) addresses of .text and the bytes up to the
# next one, from the disassembly.
llvm-objdump -d --no-show-raw-insn --section=.text "$elf" |
    awk '/^ *[0-9a-f]+:/ { a = $1; sub(":", "", a); print a }' >"$tmp/addr"
prev=""
while read -r a; do
    [[ -n "$prev" ]] && echo "$prev $(( 16#$a - 16#$prev ))"
    prev="$a"
done <"$tmp/addr" >"$tmp/sized"
cut -d' ' -f1 "$tmp/sized" | sed 's/^/0x/' | addr2line -e "$elf" -a -i >"$tmp/chains"
awk -v SRC="$src" '
    FNR == NR { size[FNR] = $2; next }
    /^0x/ { if (n) total += mine ? size[n] : 0; n++; mine = 0; next }
    index($0, SRC) == 1 { mine = 1 }
    END { if (n) total += mine ? size[n] : 0; print total + 0 }
' "$tmp/sized" "$tmp/chains"
