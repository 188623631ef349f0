// A standalone headset cannot shade every pixel with a light per case: the
// museum's point lights (KHR_lights_punctual) are kept as records, and a fixed
// pool of the nearest ones is lit each frame. A fixed count means no shader
// recompiles as the visitor walks.
import * as THREE from 'three';

const POOL = 6;

export class LightPool {
  constructor(loaded, scene) {
    this.records = [];
    const found = [];
    loaded.traverse((o) => { if (o.isPointLight) found.push(o); });
    for (const l of found) {
      const position = new THREE.Vector3();
      l.getWorldPosition(position);
      this.records.push({ position, color: l.color.clone(), intensity: l.intensity, decay: l.decay });
      l.parent.remove(l);
    }
    this.pool = [];
    for (let k = 0; k < Math.min(POOL, this.records.length); k++) {
      const light = new THREE.PointLight(0xffffff, 0, 0, 2);
      scene.add(light);
      this.pool.push(light);
    }
    this.last = null;
  }

  // Lights the records nearest to eye; does nothing until it moved 0.25 m.
  update(eye) {
    if (this.last && this.last.distanceToSquared(eye) < 0.0625) return;
    this.last = eye.clone();
    const nearest = this.records.slice().sort((a, b) =>
      a.position.distanceToSquared(eye) - b.position.distanceToSquared(eye));
    this.pool.forEach((light, k) => {
      const r = nearest[k];
      light.position.copy(r.position);
      light.color.copy(r.color);
      light.intensity = r.intensity;
      light.decay = r.decay;
    });
  }
}
