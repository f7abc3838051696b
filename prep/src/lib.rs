//! skyroute's ground tool: reads mission scenarios, builds preprocessed networks for the onboard
//! core, and lets a person see and check them.
pub mod roadmap;
pub mod scenario;
pub mod frame;
pub mod build;
pub mod mission;
pub mod route_json;
pub mod export;
pub mod render;
