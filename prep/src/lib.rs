//! skyroute's ground tool: reads mission scenarios, builds preprocessed networks for the onboard
//! core, and lets a person see and check them.
pub mod build;
pub mod build_limits;
pub mod capacity;
pub mod dem;
pub mod export;
pub mod frame;
pub mod info;
pub mod landmark;
pub mod landmark_mission;
pub mod landmark_reach;
pub mod local;
pub mod mission;
pub mod output;
pub mod plan_checks;
pub mod plan_cli;
pub mod provenance;
pub mod render;
pub mod roadmap;
pub mod roadmap_exposure;
pub mod route_geojson;
pub mod route_json;
pub mod ruz;
pub mod scenario;
pub mod terrain;
pub mod voronoi;
pub mod voronoi_mission;
