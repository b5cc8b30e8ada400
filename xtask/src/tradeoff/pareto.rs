//! The Pareto front of error against cost, and the cheapest run within an
//! error budget.

/// Indices of the runs on the Pareto front of `(cost, error)`: a run is on
/// it when no other run is at most as costly and at most as wrong, and
/// strictly better in one of the two. Returned by increasing cost.
pub fn front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0).then(points[a].1.total_cmp(&points[b].1)));
    let mut best = f64::INFINITY;
    let mut out = Vec::new();
    for i in order {
        if points[i].1 < best {
            best = points[i].1;
            out.push(i);
        }
    }
    out
}

/// The cheapest run whose error is at most `budget`, if any.
pub fn cheapest_within(points: &[(f64, f64)], budget: f64) -> Option<usize> {
    (0..points.len()).filter(|&i| points[i].1 <= budget).min_by(|&a, &b| points[a].0.total_cmp(&points[b].0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_front_keeps_runs_no_other_run_beats_on_both_counts() {
        // (cost, error)
        let p = [(10.0, 0.05), (5.0, 0.2), (20.0, 0.01), (12.0, 0.1), (5.0, 0.3), (40.0, 0.01), (1.0, 0.5)];
        assert_eq!(front(&p), vec![6, 1, 0, 2]);
    }

    #[test]
    fn the_cheapest_run_within_a_budget() {
        let p = [(10.0, 0.05), (5.0, 0.2), (20.0, 0.01), (1.0, 0.5)];
        assert_eq!(cheapest_within(&p, 0.01), Some(2));
        assert_eq!(cheapest_within(&p, 0.05), Some(0));
        assert_eq!(cheapest_within(&p, 0.2), Some(1));
        assert_eq!(cheapest_within(&p, 0.001), None);
    }
}
