//! Choosing a codec: the figures of every spec of the catalogue ([`catalogue`]), the
//! storage formats each is written to ([`formats`]), what filtering does to each float
//! form ([`filtering`]), the ranking `choose` prints ([`choose`]) and the README's recommendations
//! ([`recommend`]). `list`, `choose`
//! and `report` all read the one compiled-in catalogue, so they cannot disagree.

pub mod catalogue;
pub mod choose;
pub mod filtering;
pub mod formats;
pub mod recommend;
