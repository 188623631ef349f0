// An exhibit's label, shown when it is clicked or pointed at: as a panel on
// the page, and (in a headset, where the page is not seen) as an enlarged
// copy of its label plate floating above the case, facing the visitor.
import * as THREE from 'three';

const FLOAT_SCALE = 2.5;

function line(tag, text) {
  const el = document.createElement(tag);
  el.textContent = text;
  return el;
}

export class LabelPanel {
  constructor(scene) {
    this.dom = document.getElementById('label');
    this.floating = null;
    this.scene = scene;
  }

  show(exhibit, camera) {
    const u = exhibit.userData;
    this.dom.replaceChildren(line('h2', u.title));
    if (u.date) this.dom.appendChild(line('p', u.date));
    this.dom.appendChild(line('p', `Height ${u.height_cm.toFixed(1)} cm`));
    if (u.description) this.dom.appendChild(line('p', u.description));
    this.dom.style.display = 'block';
    this.float(exhibit, camera);
  }

  float(exhibit, camera) {
    const plate = exhibit.children.find((c) => c.isMesh && c.name.startsWith('Label'));
    if (!plate) return;
    if (this.floating) this.scene.remove(this.floating);
    this.floating = new THREE.Mesh(plate.geometry, plate.material);
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
