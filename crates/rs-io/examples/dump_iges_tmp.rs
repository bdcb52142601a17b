//! Temporary: dumps surface points of every face at the loops' sample points (JSON lines).
use rs_geom::surface::ParamSurface;
use rs_io::cad::CadModel;
use rs_spline::prelude::*;

fn main() {
    let path = std::env::args().nth(1).unwrap();
    let m = CadModel::read(&path).unwrap();
    println!("{{\"solids\": {:?}, \"shells\": [{}]}}", m.solids.iter().map(|s| s.shells.clone()).collect::<Vec<_>>(), m.shells.iter().map(|s| format!("[{:?}, {}]", s.faces, s.closed)).collect::<Vec<_>>().join(","));
    for (k, f) in m.faces.iter().enumerate() {
        let Ok(loops) = &f.loops else { println!("{{\"face\": {k}, \"error\": true}}"); continue; };
        let mut uv = Vec::new();
        for l in loops { for c in l { let (a, b) = c.param_range(); for i in 0..5 { let p = c.point_at(a + (b - a) * i as f64 / 4.0); uv.push((p.x, p.y)); } } }
        let Some(s) = &f.surface else { println!("{{\"face\": {k}, \"nosurface\": true}}"); continue; };
        let pts: Vec<String> = uv.iter().map(|&(u, v)| { let p = s.point([u, v]); let n = s.normal([u, v]).map(|n| [n.x, n.y, n.z]).unwrap_or([0.0; 3]); format!("[{u},{v},{},{},{},{},{},{}]", p.x, p.y, p.z, n[0], n[1], n[2]) }).collect();
        // edges: samples
        let mut eds = Vec::new();
        for l in &f.edges { let mut le = Vec::new(); for e in l { let s = e.sample(5); le.push(format!("[{}]", s.iter().map(|p| format!("[{},{},{}]", p.x, p.y, p.z)).collect::<Vec<_>>().join(","))); } eds.push(format!("[{}]", le.join(","))); }
        println!("{{\"face\": {k}, \"same_sense\": {}, \"pts\": [{}], \"edges\": [{}]}}", f.same_sense, pts.join(","), eds.join(","));
    }
}
