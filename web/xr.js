// WebXR locomotion. Each controller casts a ray; releasing the trigger on
// the floor teleports the visitor there (when the spot is free), on an
// exhibit shows (or closes) its label. The left thumbstick walks smoothly
// where the head looks (up: ahead, sideways: a side step) at the walking
// speed, sliding along walls and cases; the right thumbstick turns in snaps
// of SNAP_DEG about the head (pushed past SNAP_ON, it turns once, and again
// only after it came back under SNAP_OFF). The visitor's rig (the camera's
// parent) is what moves, so the headset's own tracking stays relative to it.
import * as THREE from 'three';

const DEADZONE = 0.15;
const SNAP_DEG = 30;
const SNAP_ON = 0.7;
const SNAP_OFF = 0.3;

// The xr-standard gamepad mapping puts the thumbstick at axes 2 and 3
// (touchpad-only controllers at 0 and 1).
function stick(gamepad) {
  const a = gamepad.axes;
  return a.length >= 4 ? [a[2], a[3]] : [a[0] || 0, a[1] || 0];
}

export class XrLocomotion {
  constructor(renderer, rig, camera, scene, obstacles, pickables, walker, onPick) {
    this.renderer = renderer;
    this.rig = rig;
    this.camera = camera;
    this.obstacles = obstacles;
    this.pickables = pickables;
    this.walker = walker;
    this.onPick = onPick;
    this.emulated = null;  // input sources set by a test (emulate()), in place of the session's
    this.snapArmed = true;
    this.raycaster = new THREE.Raycaster();
    this.floor = new THREE.Plane(new THREE.Vector3(0, 1, 0), 0);
    this.marker = new THREE.Mesh(new THREE.RingGeometry(0.15, 0.2, 32).rotateX(-Math.PI / 2),
      new THREE.MeshBasicMaterial({ color: 0x9fd3b0 }));
    this.marker.visible = false;
    scene.add(this.marker);
    this.controllers = [0, 1].map((i) => {
      const c = renderer.xr.getController(i);
      const ray = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3(0, 0, -5)]),
        new THREE.LineBasicMaterial({ color: 0xffffff }));
      c.add(ray);
      c.addEventListener('selectend', () => this.select(c));
      rig.add(c);
      return c;
    });
  }

  // Input sources as WebXR gives them: [{ handedness, gamepad: { axes } }].
  emulate(sources) { this.emulated = sources; }

  inputSources() {
    if (this.emulated) return this.emulated;
    const session = this.renderer.xr.getSession();
    return session ? Array.from(session.inputSources) : [];
  }

  aim(controller) {
    const m = new THREE.Matrix4().extractRotation(controller.matrixWorld);
    this.raycaster.ray.origin.setFromMatrixPosition(controller.matrixWorld);
    this.raycaster.ray.direction.set(0, 0, -1).applyMatrix4(m);
    const hit = this.raycaster.intersectObjects(this.pickables, true)[0];
    const floor = this.raycaster.ray.intersectPlane(this.floor, new THREE.Vector3());
    return { hit, floor: floor && (!hit || hit.distance > this.raycaster.ray.origin.distanceTo(floor)) ? floor : null };
  }

  select(controller) {
    const { hit, floor } = this.aim(controller);
    if (floor && this.obstacles.free(floor.x, floor.z)) {
      this.rig.position.set(floor.x, 0, floor.z);
      return;
    }
    let o = hit ? hit.object : null;
    while (o && !(o.userData && typeof o.userData.title === 'string')) o = o.parent;
    if (o) this.onPick(o);
  }

  // Turns the rig by angle (rad) about the vertical through the head, so
  // the visitor turns on the spot.
  turn(angle) {
    const head = new THREE.Vector3();
    this.camera.getWorldPosition(head);
    const q = new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(0, 1, 0), angle);
    this.rig.position.sub(head).applyQuaternion(q).add(head);
    this.rig.position.y = 0;
    this.rig.quaternion.premultiply(q);
  }

  thumbsticks(dt) {
    for (const source of this.inputSources()) {
      if (!source.gamepad) continue;
      const [x, y] = stick(source.gamepad);
      if (source.handedness === 'right') {
        if (this.snapArmed && Math.abs(x) > SNAP_ON) {
          this.turn(-Math.sign(x) * SNAP_DEG * Math.PI / 180);
          this.snapArmed = false;
        } else if (Math.abs(x) < SNAP_OFF) this.snapArmed = true;
      } else {
        const dz = (v) => (Math.abs(v) < DEADZONE ? 0 : v);
        this.walker.move(-dz(y), dz(x), dt);
      }
    }
  }

  update(dt) {
    this.marker.visible = false;
    if (this.emulated || this.renderer.xr.isPresenting) this.thumbsticks(dt);
    if (!this.renderer.xr.isPresenting) return;
    for (const c of this.controllers) {
      const { floor } = this.aim(c);
      if (floor && this.obstacles.free(floor.x, floor.z)) {
        this.marker.position.copy(floor);
        this.marker.visible = true;
      }
    }
  }
}
