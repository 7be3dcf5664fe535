//! The wave that triggers the final takeoff, traced back to its origin
//! (paper Fig. 3, green dotted lines).

use impact_model::{InterfaceCoefficients, Rod};
use impact_wave::{Direction, FrontRecord};

/// Strain coefficient from a parent front to a child born where the parent
/// arrived: reflection or transmission at an interface, `-1` at the free top,
/// `±1` at the wall (magnitude is what matters for tracing).
fn coefficient(rod: &Rod, parent: &FrontRecord, child: &FrontRecord) -> f64 {
    let layers = rod.layers();
    let n = layers.len();
    match parent.direction {
        Direction::Up if parent.layer + 1 == n => -1.0,
        Direction::Down if parent.layer == 0 => 1.0,
        Direction::Up => {
            let k =
                InterfaceCoefficients::between(&layers[parent.layer], &layers[parent.layer + 1]);
            if child.layer == parent.layer {
                k.up_reflected
            } else {
                k.up_transmitted
            }
        }
        Direction::Down => {
            let k =
                InterfaceCoefficients::between(&layers[parent.layer - 1], &layers[parent.layer]);
            if child.layer == parent.layer {
                k.down_reflected
            } else {
                k.down_transmitted
            }
        }
    }
}

/// Front ids from the origin (the impact, or a landing) to the front whose
/// arrival at the wall at `takeoff` made the rod leave for good. At each step
/// back, the parent that contributed the largest velocity jump is followed.
pub fn takeoff_path(rod: &Rod, fronts: &[FrontRecord], takeoff: f64) -> Vec<u32> {
    let tol = 1e-9 * rod.min_transit_time();
    let speed = |f: &FrontRecord| rod.layers()[f.layer].wave_speed;
    let arriving = fronts
        .iter()
        .filter(|f| {
            f.layer == 0 && f.direction == Direction::Down && (f.arrives - takeoff).abs() <= tol
        })
        .max_by(|a, b| (a.jump.abs() * speed(a)).total_cmp(&(b.jump.abs() * speed(b))));
    let Some(mut current) = arriving else {
        return Vec::new();
    };
    let mut path = vec![current.id];
    while !current.parents.is_empty() {
        let next = current
            .parents
            .iter()
            .filter_map(|&p| fronts.get(p as usize))
            .max_by(|a, b| {
                let ca = (coefficient(rod, a, current) * a.jump * speed(current)).abs();
                let cb = (coefficient(rod, b, current) * b.jump * speed(current)).abs();
                ca.total_cmp(&cb)
            });
        match next {
            Some(p) if !path.contains(&p.id) => {
                path.push(p.id);
                current = p;
            }
            _ => break,
        }
    }
    path.reverse();
    path
}
