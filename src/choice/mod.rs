//! Choosing a codec: the figures of every spec of the catalogue ([`catalogue`]) with the
//! formats each is stored in ([`crate::codecs::core::storage`]), what filtering does to each float
//! form ([`filtering`]), what a user asks ([`query`]), the ranking `choose` prints ([`choose`]), the
//! ranking by use ([`profiles`]) and the README's recommendations ([`recommend`]). `list`, `choose`
//! and `report` all read the one compiled-in catalogue, so they cannot disagree.

pub mod catalogue;
pub mod choose;
pub mod filtering;
pub mod profiles;
pub mod query;
pub mod recommend;
