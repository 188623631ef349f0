// Walking on a phone or tablet: a virtual stick in the lower left corner
// walks (up: ahead, sideways: a side step) at up to the walking speed; a
// drag anywhere else turns the head; a tap (a touch that moved less than
// TAP_PX, however long it lasted) picks what is under the finger. Pointer events of pointerType "touch"
// only, so a mouse keeps the desktop controls. The stick appears with the
// first touch.
import * as THREE from 'three';

const STICK_RADIUS = 60;      // px: the stick's travel
const TURN_PER_PX = 0.005;    // rad per px of drag
const TAP_PX = 10;            // a touch that moved less is a tap

export class TouchControls {
  constructor(camera, dom, walker, onTap) {
    this.camera = camera;
    this.walker = walker;
    this.onTap = onTap;
    this.base = document.getElementById('stick');
    this.knob = this.base.firstElementChild;
    this.stick = null;   // { id, x0, y0, dx, dy }
    this.looks = new Map();  // pointerId -> { x, y, x0, y0, t0 }
    this.euler = new THREE.Euler(0, 0, 0, 'YXZ');
    dom.style.touchAction = 'none';
    // A touch screen needs no pointer lock: the first touch hides its prompt
    // (before the tap's click could ask for the lock).
    window.addEventListener('pointerdown', (e) => {
      if (e.pointerType === 'touch') document.body.classList.add('touch');
    }, true);
    // On the window: the first touch lands on the desktop's "click to walk"
    // prompt, which it hides; touches on the label panel are the panel's.
    const mine = (e) => e.pointerType === 'touch' && !(e.target.closest && e.target.closest('#label'));
    window.addEventListener('pointerdown', (e) => { if (mine(e)) this.down(e); });
    window.addEventListener('pointermove', (e) => { if (mine(e)) this.moveTo(e); });
    window.addEventListener('pointerup', (e) => { if (mine(e)) this.up(e); });
    window.addEventListener('pointercancel', (e) => { if (mine(e)) this.up(e); });
  }

  inStick(x, y) {
    const r = this.base.getBoundingClientRect();
    const cx = r.left + r.width / 2, cy = r.top + r.height / 2;
    return Math.hypot(x - cx, y - cy) <= r.width / 2 + 20 ? { cx, cy } : null;
  }

  down(e) {
    this.base.style.display = 'block';
    const c = this.inStick(e.clientX, e.clientY);
    if (c && !this.stick) this.stick = { id: e.pointerId, x0: c.cx, y0: c.cy, dx: 0, dy: 0 };
    else this.looks.set(e.pointerId, { x: e.clientX, y: e.clientY, x0: e.clientX, y0: e.clientY });
    this.moveTo(e);
  }

  moveTo(e) {
    if (this.stick && e.pointerId === this.stick.id) {
      let dx = e.clientX - this.stick.x0, dy = e.clientY - this.stick.y0;
      const len = Math.hypot(dx, dy);
      if (len > STICK_RADIUS) dx *= STICK_RADIUS / len, dy *= STICK_RADIUS / len;
      this.stick.dx = dx;
      this.stick.dy = dy;
      this.knob.style.transform = `translate(${dx}px, ${dy}px)`;
      return;
    }
    const look = this.looks.get(e.pointerId);
    if (!look) return;
    this.euler.setFromQuaternion(this.camera.quaternion);
    this.euler.y -= (e.clientX - look.x) * TURN_PER_PX;
    this.euler.x = Math.max(-1.4, Math.min(1.4, this.euler.x - (e.clientY - look.y) * TURN_PER_PX));
    this.camera.quaternion.setFromEuler(this.euler);
    look.x = e.clientX;
    look.y = e.clientY;
  }

  up(e) {
    if (this.stick && e.pointerId === this.stick.id) {
      this.stick = null;
      this.knob.style.transform = '';
      return;
    }
    const look = this.looks.get(e.pointerId);
    this.looks.delete(e.pointerId);
    if (look && e.type === 'pointerup' && Math.hypot(e.clientX - look.x0, e.clientY - look.y0) < TAP_PX) {
      this.onTap(e.clientX, e.clientY);
    }
  }

  update(dt) {
    if (this.stick) this.walker.move(-this.stick.dy / STICK_RADIUS, this.stick.dx / STICK_RADIUS, dt);
  }
}
