use super::*;

#[test]
fn link_choices_parse() {
    assert_eq!("sim".parse::<LinkChoice>(), Ok(LinkChoice::Sim));
    assert_eq!(
        "serial:/dev/ttyACM0@57600".parse::<LinkChoice>(),
        Ok(LinkChoice::Serial("/dev/ttyACM0@57600".into()))
    );
    assert!("serial:".parse::<LinkChoice>().is_err());
    assert!("can".parse::<LinkChoice>().unwrap_err().contains("can"));
}

fn twin_session(config: Option<PathBuf>) -> Session {
    Session::load(&SessionSpec {
        config,
        ..SessionSpec::twin(None)
    })
    .unwrap()
}

#[test]
fn a_world_in_memory_drives_the_twin_and_keeps_the_configs_block_count() {
    let mut world = World::default_arena();
    world.name = "two blocks".into();
    world.blocks.truncate(2);
    let spec = SessionSpec::twin(None);
    let session = Session::load_with_world(&spec, world.clone()).unwrap();
    // The mission is not told the truth: it delivers what it finds.
    let configured = Config::default().mission.total_blocks;
    assert_eq!(session.config.mission.total_blocks, configured);
    let (_, link) = session.into_link();
    assert_eq!(link.ground_truth().unwrap().world().name, "two blocks");
    let ros2 = SessionSpec {
        link: LinkChoice::Ros2(Ros2Target::default()),
        ..spec
    };
    let err = Session::load_with_world(&ros2, world)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("needs the twin"), "{err}");
}

#[test]
fn the_blind_distance_follows_the_camera_unless_the_config_sets_it() {
    let blind = |s: &Session| s.config.mission.blind_distance.unwrap();
    // The ideal sensor: its 0.10 m least range plus half a 0.05 m block.
    let mut ideal = twin_session(None);
    assert!((blind(&ideal) - 0.125).abs() < 1e-9);
    if cfg!(feature = "vision") {
        // The rendered camera loses a block marker 0.232 m ahead.
        ideal
            .use_sim_camera(None, crate::sim::CameraFrames::Whole)
            .unwrap();
        assert!((blind(&ideal) - 0.232).abs() < 0.002, "{}", blind(&ideal));
    }
    let dir = std::env::temp_dir().join(format!("navdeck-blind-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("blind.toml");
    std::fs::write(&file, "[mission]\nblind_distance = 0.3\n").unwrap();
    let mut set = twin_session(Some(file));
    if cfg!(feature = "vision") {
        set.use_sim_camera(None, crate::sim::CameraFrames::Whole)
            .unwrap();
    }
    assert_eq!(set.config.mission.blind_distance, Some(0.3));
    std::fs::remove_dir_all(dir).unwrap();
}
