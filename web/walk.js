// Desktop walking: pointer lock turns the head with the mouse, W A S D (or
// the arrow keys) walk at a visitor's pace, collisions slide along walls and
// cases; a click picks what is under the crosshair. move() is also what the
// phone's virtual stick (touch.js) drives.
import * as THREE from 'three';
import { PointerLockControls } from 'three/addons/controls/PointerLockControls.js';

export const SPEED = 1.4;  // m/s

export class Walker {
  constructor(camera, rig, dom, obstacles) {
    this.camera = camera;
    this.rig = rig;
    this.obstacles = obstacles;
    this.controls = new PointerLockControls(camera, dom);
    this.keys = new Set();
    this.pick = null;
    const start = document.getElementById('start');
    start.addEventListener('click', () => this.controls.lock());
    this.controls.addEventListener('lock', () => { start.style.display = 'none'; });
    this.controls.addEventListener('unlock', () => { start.style.display = 'flex'; });
    document.addEventListener('keydown', (e) => this.keys.add(e.code));
    document.addEventListener('keyup', (e) => this.keys.delete(e.code));
    dom.addEventListener('mousedown', () => { if (this.controls.isLocked && this.pick) this.pick(); });
  }

  // Walks ahead (forward +) and side (right +), each in [-1, 1], for dt s
  // at SPEED, along the floor in the direction the eyes look.
  move(ahead, side, dt) {
    if (!ahead && !side) return;
    const forward = new THREE.Vector3();
    this.camera.getWorldDirection(forward);
    forward.y = 0;
    forward.normalize();
    const right = new THREE.Vector3(-forward.z, 0, forward.x);
    const step = forward.multiplyScalar(ahead).add(right.multiplyScalar(side));
    if (step.length() > 1) step.normalize();
    step.multiplyScalar(SPEED * dt);
    this.obstacles.move(this.rig.position, step.x, step.z);
  }

  update(dt) {
    if (!this.controls.isLocked) return;
    const k = this.keys;
    const ahead = (k.has('KeyW') || k.has('ArrowUp') ? 1 : 0) - (k.has('KeyS') || k.has('ArrowDown') ? 1 : 0);
    const side = (k.has('KeyD') || k.has('ArrowRight') ? 1 : 0) - (k.has('KeyA') || k.has('ArrowLeft') ? 1 : 0);
    this.move(ahead, side, dt);
  }
}
