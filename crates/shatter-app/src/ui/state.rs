//! The whole user-interface state as one plain struct, and the decisions it makes
//! (which command a button or a click produces) as pure methods.

use bevy::prelude::Resource;
use glam::Vec3;

use crate::commands::{BondModel, ForceSpec, ObjectId, ObjectSpec, ProjectileSpec, SimCommand};
use crate::error::AppError;
use crate::ui::forms::{
    AddObjectForm, FieldErrors, FireForm, ForceForm, MeshCheck, ProjectileLoad, SceneFileForm,
    TransformForm,
};

/// Which page of the Add Object panel is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AddObjectPage {
    /// Panel closed.
    #[default]
    Closed,
    /// Shape and fracture parameters.
    Parameters,
    /// Position and scale (Draw, Apply, Back).
    Transform,
}

/// What a left click in the 3D view does.
#[derive(Debug, Clone, PartialEq)]
pub enum ClickOutcome {
    /// Send this command.
    Command(SimCommand),
    /// Open this object's properties (Edit mode).
    Edit(ObjectId),
    /// Nothing.
    Nothing,
}

/// The user interface's state: every form, every toggle, every message.
#[derive(Resource, Debug, Clone, Default)]
pub struct UiState {
    /// Add Object page shown.
    pub add_page: AddObjectPage,
    /// Add Object parameters.
    pub add: AddObjectForm,
    /// Transform page.
    pub transform: TransformForm,
    /// Errors of the Add Object / transform pages.
    pub add_errors: FieldErrors,
    /// The object the transform page is editing: the one made by Draw, or the one
    /// clicked in Edit mode.
    pub target: Option<ObjectId>,
    /// The target's specification as last built (what the panels do not show is kept
    /// from it when the fields are drawn again).
    pub base: Option<ObjectSpec>,
    /// Draw was pressed for a new object whose id has not come back yet.
    pub awaiting_new_id: bool,
    /// Fire panel fields.
    pub fire: FireForm,
    /// Errors of the Fire panel.
    pub fire_errors: FieldErrors,
    /// The projectile clicks fire (set by OK; a click sets its launch and aim points).
    pub projectile: ProjectileSpec,
    /// Add Force fields.
    pub force_form: ForceForm,
    /// Errors of the Add Force panel.
    pub force_errors: FieldErrors,
    /// The explosion clicks set off (updated whenever the fields are valid).
    pub force: ForceSpec,
    /// Edit toggle.
    pub edit_mode: bool,
    /// Delete toggle.
    pub delete_mode: bool,
    /// Bond model for new objects.
    pub bond_model: Option<BondModel>,
    /// Scene file field.
    pub scene_file: SceneFileForm,
    /// Errors of the scene file field.
    pub scene_errors: FieldErrors,
    /// Last message from the simulation (errors of commands, saves, loads).
    pub status: String,
}

impl UiState {
    /// "Next" on the parameters page: validate it (with the current transform) and show
    /// the transform page.
    pub fn next_page(&mut self, check: MeshCheck<'_>) {
        match self
            .add
            .validate(&self.transform, check, self.base.as_ref())
        {
            Ok(_) => {
                self.add_errors = FieldErrors::default();
                self.add_page = AddObjectPage::Transform;
            }
            Err(e) => self.add_errors = e,
        }
    }

    /// "Draw": build (or rebuild) the object with the current fields.
    pub fn draw(&mut self, check: MeshCheck<'_>) -> Option<SimCommand> {
        let spec = self.validated_object(check)?;
        self.base = Some(spec.clone());
        Some(match self.target {
            Some(id) => SimCommand::EditObject(id, Box::new(spec)),
            None => {
                self.awaiting_new_id = true;
                SimCommand::AddObject(Box::new(spec))
            }
        })
    }

    /// "Apply": like Draw, then close the panel; the object stays.
    pub fn apply(&mut self, check: MeshCheck<'_>) -> Option<SimCommand> {
        let cmd = self.draw(check)?;
        self.close_add_panel();
        Some(cmd)
    }

    /// "Back": return to the parameters page.
    pub fn back(&mut self) {
        self.add_page = AddObjectPage::Parameters;
    }

    /// Open the Add Object panel for a new object.
    pub fn open_add_panel(&mut self) {
        self.target = None;
        self.base = None;
        self.awaiting_new_id = false;
        self.add_errors = FieldErrors::default();
        self.add_page = AddObjectPage::Parameters;
    }

    /// Close the Add Object panel, forgetting which object it was editing.
    pub fn close_add_panel(&mut self) {
        self.add_page = AddObjectPage::Closed;
        self.target = None;
        self.base = None;
    }

    /// The simulation created an object (answer to Draw's AddObject).
    pub fn object_added(&mut self, id: ObjectId) {
        if self.awaiting_new_id {
            self.awaiting_new_id = false;
            if self.add_page != AddObjectPage::Closed {
                self.target = Some(id);
            }
        }
    }

    /// The simulation refused `cmd` with `error`: show its message in the status line and,
    /// for an object that could not be built, next to the Add Object fields too (the
    /// user's fields stay as they were, so they can be corrected).
    pub fn command_failed(&mut self, cmd: &SimCommand, error: AppError) {
        self.status = error.to_string();
        if matches!(cmd, SimCommand::AddObject(_) | SimCommand::EditObject(..)) {
            if matches!(cmd, SimCommand::AddObject(_)) {
                self.awaiting_new_id = false;
                self.base = None;
            }
            self.add_errors.insert("object", error);
        }
    }

    /// Open the properties of `id` (Edit mode) with its current specification.
    pub fn edit_object(&mut self, id: ObjectId, spec: &ObjectSpec) {
        let (add, transform) = AddObjectForm::from_spec(spec);
        self.add = add;
        self.transform = transform;
        self.target = Some(id);
        self.base = Some(spec.clone());
        self.awaiting_new_id = false;
        self.add_errors = FieldErrors::default();
        self.add_page = AddObjectPage::Parameters;
    }

    /// "OK" of the Fire panel: keep the projectile if the fields are valid.
    pub fn fire_ok(&mut self, load: ProjectileLoad<'_>) -> bool {
        match self.fire.validate(load) {
            Ok(p) => {
                self.projectile = p;
                self.fire_errors = FieldErrors::default();
                true
            }
            Err(e) => {
                self.fire_errors = e;
                false
            }
        }
    }

    /// Re-read the Add Force fields; invalid fields keep the previous explosion.
    pub fn update_force(&mut self) {
        match self.force_form.validate() {
            Ok(f) => {
                self.force = f;
                self.force_errors = FieldErrors::default();
            }
            Err(e) => {
                self.force_errors = e;
                self.force.enabled = self.force_form.enabled;
            }
        }
    }

    /// Toggle Edit (turns Delete off).
    pub fn toggle_edit(&mut self) {
        self.edit_mode = !self.edit_mode;
        if self.edit_mode {
            self.delete_mode = false;
        }
    }

    /// Toggle Delete (turns Edit off).
    pub fn toggle_delete(&mut self) {
        self.delete_mode = !self.delete_mode;
        if self.delete_mode {
            self.edit_mode = false;
        }
    }

    /// What a left click does. `eye` is the camera position, `dir` the unit ray through
    /// the cursor, `hit` the object and point under it.
    pub fn click(&self, eye: Vec3, dir: Vec3, hit: Option<(ObjectId, Vec3)>) -> ClickOutcome {
        if self.delete_mode {
            return match hit {
                Some((id, _)) => ClickOutcome::Command(SimCommand::DeleteObject(id)),
                None => ClickOutcome::Nothing,
            };
        }
        if self.edit_mode {
            return match hit {
                Some((id, _)) => ClickOutcome::Edit(id),
                None => ClickOutcome::Nothing,
            };
        }
        let target = hit.map(|(_, p)| p).or_else(|| ground_hit(eye, dir));
        if self.force.enabled {
            return match target {
                Some(position) => ClickOutcome::Command(SimCommand::Explode {
                    position,
                    radius: self.force.radius,
                    power: self.force.power,
                }),
                None => ClickOutcome::Nothing,
            };
        }
        let to = target.unwrap_or(eye + dir * FAR_AIM);
        // Launch a little in front of the camera so the projectile does not start inside
        // the near plane.
        let from = eye + dir * LAUNCH_OFFSET;
        ClickOutcome::Command(SimCommand::Fire(ProjectileSpec {
            from,
            to,
            ..self.projectile.clone()
        }))
    }

    fn validated_object(&mut self, check: MeshCheck<'_>) -> Option<ObjectSpec> {
        match self
            .add
            .validate(&self.transform, check, self.base.as_ref())
        {
            Ok(spec) => {
                self.add_errors = FieldErrors::default();
                Some(spec)
            }
            Err(e) => {
                self.add_errors = e;
                None
            }
        }
    }
}

/// Distance of the aim point when the ray hits nothing.
pub const FAR_AIM: f32 = 200.0;
/// Distance in front of the camera where projectiles start.
pub const LAUNCH_OFFSET: f32 = 1.0;

/// Where a ray meets the ground plane `y = 0`, if in front of the eye.
pub fn ground_hit(eye: Vec3, dir: Vec3) -> Option<Vec3> {
    if dir.y >= -1e-6 {
        return None;
    }
    let t = -eye.y / dir.y;
    (t > 0.0).then(|| eye + dir * t)
}
