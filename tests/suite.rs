//! navdeck's integration tests, one binary: each file beside this one is a module, and the
//! helpers they share are declared here once. One binary links navdeck once instead of
//! once per file, which keeps the test build and `target/` small. `ros2_interop` stays a
//! binary of its own, because the suite also builds it for ROS 2 Humble.
//!
//! Run one file's tests with its module name: `cargo test --test suite console::`.

// Helpers, a file each (see common/README.md).
#[path = "common"]
mod common {
    pub mod app_with;
    pub mod binary;
    pub mod clear_round;
    pub mod console_command;
    pub mod default_app;
    pub mod hold;
    pub mod key;
    pub mod logged;
    pub mod press;
    pub mod recording;
    pub mod render;
    pub mod render_at;
    pub mod replay_played;
    pub mod run_loop;
    pub mod scratch;
    pub mod screen;
    pub mod script;
    pub mod switched_link;
    pub mod until;
    pub use {
        app_with::*, binary::*, clear_round::*, console_command::*, default_app::*, hold::*,
        key::*, logged::*, press::*, recording::*, render::*, render_at::*, replay_played::*,
        run_loop::*, scratch::*, screen::*, script::*, switched_link::*, until::*,
    };
}
#[path = "plan_support"]
mod plan_support {
    pub mod arena;
    pub mod random;
    pub mod reference;
    pub use {arena::*, random::*, reference::*};
}
#[path = "pty_support"]
mod pty_support {
    pub mod console;
    pub mod hang_up;
    pub use console::*;
}
#[path = "serial_emulator"]
mod serial_emulator {
    pub mod faults;
    pub mod firmware;
    pub mod frames;
    pub mod mute;
    pub mod requests;
    pub use firmware::*;
}
#[cfg(feature = "vision")]
#[path = "vision_support"]
mod vision_support {
    pub mod arena;
    pub mod level;
    pub use {arena::*, level::*};
}
mod cyclone_peer;
mod mission_rig;
mod python_support;
mod ros2_support;

// The tests, a file each.
mod arm_cli;
mod camera_panel;
mod camera_pipeline;
mod cli;
mod collision_monitor;
mod console;
mod console_keys;
mod console_route;
mod console_slam;
mod console_truth;
mod console_zones;
mod control_follow;
mod dead_terminal;
mod degradation;
mod faults;
mod fleet;
mod fleet_explore;
mod fleet_record;
mod generated_sweep;
mod gripper;
mod hangup;
mod hostile;
mod key_bytes;
mod keymaps;
mod lane;
mod lidar_loop;
mod lidar_slam;
mod map_belief;
mod map_io;
mod map_load;
mod mcl;
mod mission;
mod mission_drop;
mod mission_machine;
mod mission_objects;
mod mission_recovery;
mod nav2_world;
mod navigation;
mod pilot;
mod plan_astar;
mod plan_post;
mod pty;
mod readme;
mod record_console;
mod record_python;
mod record_replay;
mod replay_screen;
mod ros2_grow;
mod ros2_link;
mod ros2_topics;
mod route_cli;
mod route_mode;
mod serial_link;
mod serial_measure;
mod sim_camera_readable;
mod sim_faults;
mod sim_twin;
mod sim_world;
mod slam_ekf;
mod snapshots;
mod soak;
mod tags_cli;
mod vision;
mod vision_survey;
mod waypoints;
mod world_generate;
mod zones;
