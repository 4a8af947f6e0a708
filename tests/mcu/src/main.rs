//! Measures sightline micro-kernels on Cortex-M under QEMU.
//!
//! The command line comes from semihosting (`SYS_GET_CMDLINE`; QEMU's
//! `-semihosting-config ...,arg=A,arg=B`):
//!
//! - `run KERNEL SCALAR N`: runs `N` operations of `KERNEL` (see
//!   [`kernels::KERNELS`]) for `SCALAR` (`I16F16` or `f32`) and exits. Run it
//!   with N and with 0 under the qemu-insn plugin: the difference in guest
//!   instructions over N is the cost per operation. Give N with a fixed
//!   number of digits (e.g. `000256` and `000000`) so that parsing costs the
//!   same in both runs.
//! - `hash`: prints FNV-1a of the I16F16 and f32 results
//!   (`hash I16F16 0x…`, `hash f32 0x…`) and fails if the I16F16 hash differs
//!   from [`kernels::FX_HASH_EXPECTED`], which the host test checks too, or
//!   if a `solve3x3` system fails to solve.
//!
//! Exit status (semihosting): 0 on success, 1 on a bad command line,
//! mismatch or panic.

#![no_std]
#![no_main]

mod kernels;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln, nr, syscall1};
use panic_semihosting as _;
use sightline::scalar::I16F16;

/// The semihosting command line (QEMU joins its `arg=` values with spaces).
fn cmdline(buf: &mut [u8]) -> &str {
    let mut block = [buf.as_mut_ptr() as usize, buf.len()];
    // SAFETY: SYS_GET_CMDLINE writes at most `block[1]` bytes into `buf`
    // and the length back into `block[1]`.
    let rc = unsafe { syscall1(nr::GET_CMDLINE, block.as_mut_ptr() as usize) };
    if rc != 0 {
        return "";
    }
    let len = block[1].min(buf.len());
    core::str::from_utf8(&buf[..len]).unwrap_or("")
}

fn parse_u32(s: &str) -> Option<u32> {
    let mut v: u32 = 0;
    if s.is_empty() {
        return None;
    }
    for c in s.bytes() {
        if !c.is_ascii_digit() {
            return None;
        }
        v = v.checked_mul(10)?.checked_add((c - b'0') as u32)?;
    }
    Some(v)
}

fn exit(ok: bool) -> ! {
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    #[allow(clippy::empty_loop)]
    loop {}
}

fn usage(cmd: &str) -> ! {
    hprintln!(
        "bad command line {:?}; expected `run KERNEL SCALAR N` or `hash`",
        cmd
    );
    hprintln!("kernels: {:?}; scalars: I16F16, f32", kernels::KERNELS);
    exit(false)
}

#[entry]
fn main() -> ! {
    let mut buf = [0u8; 128];
    let cmd = cmdline(&mut buf);
    let mut args = cmd.split_ascii_whitespace();
    match args.next() {
        Some("run") => {
            let (Some(kernel), Some(scalar), Some(n), None) = (
                args.next(),
                args.next(),
                args.next().and_then(parse_u32),
                args.next(),
            ) else {
                usage(cmd)
            };
            let ok = match scalar {
                "I16F16" => kernels::run::<I16F16>(kernel, n),
                "f32" => kernels::run::<f32>(kernel, n),
                _ => false,
            };
            if !ok {
                usage(cmd)
            }
            exit(true)
        }
        Some("hash") => {
            let fx = kernels::hash_results::<I16F16>();
            let fl = kernels::hash_results::<f32>();
            hprintln!("hash I16F16 {:#018x}", fx);
            hprintln!("hash f32 {:#018x}", fl);
            let mut ok = true;
            if fx != kernels::FX_HASH_EXPECTED {
                hprintln!(
                    "I16F16 hash mismatch: expected {:#018x}",
                    kernels::FX_HASH_EXPECTED
                );
                ok = false;
            }
            if !kernels::all_systems_solve::<I16F16>() || !kernels::all_systems_solve::<f32>() {
                hprintln!("a solve3x3 system failed to solve");
                ok = false;
            }
            exit(ok)
        }
        _ => usage(cmd),
    }
}
