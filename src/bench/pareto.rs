//! The Pareto front of (time, error) points and the `--max-error` pick.
//!
//! A configuration is on the front when no other one is at most as slow
//! and at most as wrong, and strictly better in one of the two. The
//! cheapest configuration within an error budget is always on the front
//! (a cheaper one within the budget would dominate it), so `--max-error`
//! only has to look there.

/// One measured configuration: cost and error, both finite and ≥ 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    pub time: f64,
    pub error: f64,
}

/// Indices of the points on the front, ordered by increasing time (and so
/// decreasing error). Of exact duplicates the first is kept.
pub fn front(points: &[Point]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| {
        points[a]
            .time
            .total_cmp(&points[b].time)
            .then(points[a].error.total_cmp(&points[b].error))
            .then(a.cmp(&b))
    });
    let mut out = Vec::new();
    let mut best_error = f64::INFINITY;
    for i in order {
        // Sorted by time, so a point is on the front exactly when it is
        // strictly more accurate than everything at most as slow.
        if points[i].error < best_error {
            best_error = points[i].error;
            out.push(i);
        }
    }
    out
}

/// The cheapest point whose error is at most `max_error`, or `None` when
/// no point is that accurate.
pub fn cheapest_within(points: &[Point], max_error: f64) -> Option<usize> {
    front(points)
        .into_iter()
        .find(|&i| points[i].error <= max_error)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(time: f64, error: f64) -> Point {
        Point { time, error }
    }

    #[test]
    fn front_keeps_exactly_the_non_dominated_points() {
        let points = [
            p(1.0, 0.5),  // 0: cheapest
            p(2.0, 0.6),  // 1: dominated by 0
            p(2.0, 0.2),  // 2: front
            p(3.0, 0.2),  // 3: dominated by 2 (same error, slower)
            p(5.0, 0.0),  // 4: front (exact)
            p(4.0, 0.25), // 5: dominated by 2
        ];
        assert_eq!(front(&points), vec![0, 2, 4]);
        // Brute force agrees: i is on the front iff nothing dominates it.
        for (i, a) in points.iter().enumerate() {
            let dominated = points.iter().enumerate().any(|(j, b)| {
                j != i
                    && b.time <= a.time
                    && b.error <= a.error
                    && (b.time < a.time || b.error < a.error)
            });
            assert_eq!(front(&points).contains(&i), !dominated, "point {i}");
        }
    }

    #[test]
    fn max_error_picks_the_cheapest_point_within_the_budget() {
        let points = [p(1.0, 0.5), p(2.0, 0.2), p(5.0, 0.0), p(0.5, 0.9)];
        assert_eq!(cheapest_within(&points, 1.0), Some(3));
        assert_eq!(cheapest_within(&points, 0.5), Some(0));
        assert_eq!(cheapest_within(&points, 0.3), Some(1));
        assert_eq!(cheapest_within(&points, 0.0), Some(2));
        assert_eq!(cheapest_within(&points, -1.0), None);
        // The pick is the cheapest of all points within the budget, not
        // only of the front.
        for e in [0.0, 0.1, 0.2, 0.3, 0.5, 0.9, 2.0] {
            let brute = (0..points.len())
                .filter(|&i| points[i].error <= e)
                .min_by(|&a, &b| points[a].time.total_cmp(&points[b].time));
            assert_eq!(cheapest_within(&points, e), brute, "budget {e}");
        }
    }

    #[test]
    fn empty_and_single() {
        assert!(front(&[]).is_empty());
        assert_eq!(front(&[p(1.0, 1.0)]), vec![0]);
    }
}
