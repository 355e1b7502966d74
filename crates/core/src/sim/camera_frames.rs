//! How much of each frame the twin's rendered camera draws (`--sim-camera`).

/// What the rendered camera makes of each frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CameraFrames {
    /// The whole picture, noise and all, with a thumbnail for the console's camera panel.
    #[default]
    Whole,
    /// Only the regions round markers whose sightings the detector could accept: the
    /// sightings are those of the whole picture, but there is no thumbnail, and the IDs
    /// and refusals reported are those of the drawn regions only (`navdeck mission`).
    Readable,
}
