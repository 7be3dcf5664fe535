//! Contact bookkeeping shared by the engines: intervals, raw separations and the
//! paper's filtered bounce count.

/// The wall-contact history of one run. Contact starts at `t = 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactHistory {
    intervals: Vec<[f64; 2]>,
    open_since: Option<f64>,
}

impl Default for ContactHistory {
    fn default() -> Self {
        Self::new()
    }
}

impl ContactHistory {
    /// In contact since `t = 0`.
    pub fn new() -> Self {
        Self {
            intervals: Vec::new(),
            open_since: Some(0.0),
        }
    }

    /// Whether the rod touches the wall now (a contact interval is open).
    pub fn in_contact(&self) -> bool {
        self.open_since.is_some()
    }

    /// The rod leaves the wall at `t` (ignored when already free).
    pub fn separate(&mut self, t: f64) {
        if let Some(start) = self.open_since.take() {
            self.intervals.push([start, t]);
        }
    }

    /// The rod touches the wall again at `t` (ignored when already in contact).
    pub fn reconnect(&mut self, t: f64) {
        if self.open_since.is_none() {
            self.open_since = Some(t);
        }
    }

    /// Closed intervals, plus the open one closed at `end` if still in contact.
    pub fn intervals(&self, end: f64) -> Vec<[f64; 2]> {
        let mut all = self.intervals.clone();
        if let Some(start) = self.open_since {
            all.push([start, end]);
        }
        all
    }

    /// Raw number of separations.
    pub fn separations(&self) -> u32 {
        self.intervals.len() as u32
    }

    /// The paper's `N_b`: 1 + number of flights (separation then reconnection)
    /// lasting longer than `min_flight` (the paper uses `min(t1, t2)`).
    pub fn bounces(&self, min_flight: f64) -> u32 {
        let flights = self
            .intervals
            .windows(2)
            .filter(|w| w[1][0] - w[0][1] > min_flight)
            .count();
        let trailing = match (self.intervals.last(), self.open_since) {
            (Some(last), Some(start)) if start - last[1] > min_flight => 1,
            _ => 0,
        };
        1 + (flights + trailing) as u32
    }

    /// `t_c`: the last separation, or `end` when still in contact.
    pub fn contact_time(&self, end: f64) -> f64 {
        match (self.open_since, self.intervals.last()) {
            (Some(_), _) => end,
            (None, Some(last)) => last[1],
            (None, None) => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_flights_are_not_bounces() {
        let mut h = ContactHistory::new();
        h.separate(1.0);
        h.reconnect(1.05); // short flight
        h.separate(2.0);
        h.reconnect(3.0); // long flight
        h.separate(4.0);
        assert_eq!(h.separations(), 3);
        assert_eq!(h.bounces(0.1), 2);
        assert_eq!(h.contact_time(10.0), 4.0);
        assert_eq!(h.intervals(10.0).len(), 3);
    }

    #[test]
    fn open_contact_ends_at_the_end() {
        let mut h = ContactHistory::new();
        h.separate(1.0);
        h.reconnect(2.0);
        assert_eq!(h.contact_time(5.0), 5.0);
        assert_eq!(h.intervals(5.0), vec![[0.0, 1.0], [2.0, 5.0]]);
        assert_eq!(h.bounces(0.5), 2);
    }
}
