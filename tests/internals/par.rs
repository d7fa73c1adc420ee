#[test]
fn keeps_the_order_of_its_input() {
    let items: Vec<u64> = (0..1000).collect();
    let want: Vec<u64> = items.iter().map(|x| x * x + 1).collect();
    assert_eq!(unitpack::support::par::map(&items, |x| x * x + 1), want);
    assert!(unitpack::support::par::map(&[] as &[u64], |x| *x).is_empty());
}
