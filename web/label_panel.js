// An exhibit's label, shown when it is clicked, tapped or pointed at: as a
// panel on the page, and (in a headset, where the page is not seen) as an
// enlarged copy of its label plate floating above the case, facing the
// visitor. Both close together: the panel's close button, a click or tap on
// nothing, picking the same exhibit again in a headset, or walking away
// (farther than CLOSE_DISTANCE from the case).
import * as THREE from 'three';

const FLOAT_SCALE = 2.5;
const CLOSE_DISTANCE = 4;  // m

function line(tag, text) {
  const el = document.createElement(tag);
  el.textContent = text;
  return el;
}

export class LabelPanel {
  constructor(scene) {
    this.dom = document.getElementById('label');
    this.floating = null;
    this.exhibit = null;
    this.scene = scene;
  }

  show(exhibit, camera) {
    const u = exhibit.userData;
    const close = line('button', '\u00d7');
    close.className = 'close';
    close.title = 'close';
    close.addEventListener('click', (e) => { e.stopPropagation(); this.hide(); });
    this.dom.replaceChildren(close, line('h2', u.title));
    if (u.date) this.dom.appendChild(line('p', u.date));
    if (u.size) this.dom.appendChild(line('p', u.size));
    if (u.note) this.dom.appendChild(line('p', u.note));
    if (u.description) this.dom.appendChild(line('p', u.description));
    this.dom.style.display = 'block';
    this.exhibit = exhibit;
    this.float(exhibit, camera);
  }

  // A headset's pick: the same exhibit again closes its label.
  toggle(exhibit, camera) {
    if (this.exhibit === exhibit) this.hide();
    else this.show(exhibit, camera);
  }

  hide() {
    this.dom.style.display = 'none';
    if (this.floating) this.scene.remove(this.floating);
    this.floating = null;
    this.exhibit = null;
  }

  get open() { return this.exhibit !== null; }

  // Closes the label once the visitor's eye is far from its case.
  update(eye) {
    if (!this.exhibit) return;
    const at = new THREE.Vector3();
    this.exhibit.getWorldPosition(at);
    if (Math.hypot(at.x - eye.x, at.z - eye.z) > CLOSE_DISTANCE) this.hide();
  }

  float(exhibit, camera) {
    const plate = exhibit.children.find((c) => c.isMesh && c.name.startsWith('Label'));
    if (this.floating) this.scene.remove(this.floating);
    this.floating = null;
    if (!plate) return;
    this.floating = new THREE.Mesh(plate.geometry, plate.material);
    this.floating.name = 'Floating label';
    const top = new THREE.Box3().setFromObject(exhibit).max.y;
    const at = new THREE.Vector3();
    exhibit.getWorldPosition(at);
    at.y = top + 0.35;
    this.floating.position.copy(at);
    this.floating.scale.copy(plate.scale).multiplyScalar(FLOAT_SCALE);
    const eye = new THREE.Vector3();
    camera.getWorldPosition(eye);
    this.floating.lookAt(eye.x, at.y, eye.z);
    this.scene.add(this.floating);
  }
}
