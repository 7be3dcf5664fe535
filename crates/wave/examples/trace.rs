use impact_model::Bilayer;
use impact_wave::{WaveConfig, WaveEngine};
fn main() {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().unwrap())
        .collect();
    let rod = Bilayer::new(a[0], a[1])
        .unwrap()
        .scene()
        .validate()
        .unwrap();
    let mut e = WaveEngine::new(&rod, WaveConfig::default()).unwrap();
    let skip = a[2] as u64;
    let show = a[3] as u64;
    for i in 0..skip + show {
        let s = e.step().unwrap();
        if i >= skip {
            println!("{i} t={:.17} {:?} {:?}", s.time, s.kind, e.contact_state());
        }
    }
}
