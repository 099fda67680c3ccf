//! Times `tetrahedralize` on uniform random points and reports peak memory.
//!
//! `cargo run --release -p shatter-geom --example delaunay_timing -- [SIZES] [--write FILE]`
//! (SIZES comma separated, default `1000,10000,100000,1000000`). `--write FILE` also saves
//! the largest point set as `x y z` lines (the input of `bench/cgal/compare.sh`); `--read
//! FILE` times that file instead of random points.
//!
//! Memory: the resident-set high-water mark (`VmHWM`) is reset before each run
//! (`/proc/self/clear_refs`), so `peak - before` is what the call itself needed on top of
//! the input points; the result's own size is printed too.

use std::io::{BufRead, Write};
use std::time::Instant;

use shatter_geom::DVec3;
use shatter_geom::delaunay::tetrahedralize;
use shatter_geom::sampling::uniform;

fn status_kb(key: &str) -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// CPU time of the whole process in seconds, every thread's (user + system time from
/// `/proc/self/stat`, in clock ticks of 10 ms), so that a loaded machine inflates the
/// figures less than wall time; from 200,000 points the work runs on two threads.
fn cpu_secs() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // Fields after the command name (which may hold spaces) in parentheses.
            let rest = &s[s.rfind(')')? + 2..];
            let f: Vec<&str> = rest.split_whitespace().collect();
            Some(f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?)
        })
        .map_or(f64::NAN, |ticks| ticks / 100.0)
}

fn run(points: &[DVec3]) -> Result<(), Box<dyn std::error::Error>> {
    let n = points.len();
    // Reset the high-water mark to the current RSS (Linux >= 4.0).
    let _ = std::fs::write("/proc/self/clear_refs", "5");
    let before = status_kb("VmRSS:").unwrap_or(0);
    let t0 = Instant::now();
    let c0 = cpu_secs();
    let mut t = tetrahedralize(points)?;
    let cpu = cpu_secs() - c0;
    let secs = t0.elapsed().as_secs_f64();
    let peak = status_kb("VmHWM:").unwrap_or(0);
    t.shrink_to_fit();
    let result_bytes = t.heap_bytes();
    println!(
        "{n:>9} points {:>9} tets {:>8.1} ms wall {:>8.1} ms cpu {:>5.2} Mpts/s(cpu)  peak +{:>6.1} B/pt  result {:>6.1} B/pt",
        t.len(),
        secs * 1e3,
        cpu * 1e3,
        n as f64 / cpu / 1e6,
        (peak.saturating_sub(before)) as f64 * 1024.0 / n as f64,
        result_bytes as f64 / n as f64,
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut sizes = vec![1_000, 10_000, 100_000, 1_000_000];
    let mut write = None;
    let mut read = None;
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--write" => {
                write = args.get(i + 1).cloned();
                i += 1;
            }
            "--read" => {
                read = args.get(i + 1).cloned();
                i += 1;
            }
            s => sizes = s.split(',').map(str::parse).collect::<Result<_, _>>()?,
        }
        i += 1;
    }
    if let Some(path) = read {
        let f = std::io::BufReader::new(std::fs::File::open(&path)?);
        let mut pts = Vec::new();
        for line in f.lines() {
            let line = line?;
            let v: Vec<f64> = line
                .split_whitespace()
                .map(str::parse)
                .collect::<Result<_, _>>()?;
            if v.len() == 3 {
                pts.push(DVec3::new(v[0], v[1], v[2]));
            }
        }
        return run(&pts);
    }
    for &n in &sizes {
        let pts = uniform(n, 1);
        run(&pts)?;
        if let (Some(path), Some(&max)) = (&write, sizes.iter().max())
            && n == max
        {
            let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
            for p in &pts {
                writeln!(f, "{:?} {:?} {:?}", p.x, p.y, p.z)?;
            }
        }
    }
    Ok(())
}
