// What a visitor cannot walk through: the room's walls and every exhibit's
// footprint (pedestal and case), as rectangles on the floor grown by the
// visitor's radius.
import * as THREE from 'three';

const RADIUS = 0.25;  // m

export class Obstacles {
  constructor(info, exhibits) {
    const [w, d] = info.room;
    this.xmax = w / 2 - RADIUS;
    this.zmax = d / 2 - RADIUS;
    this.boxes = exhibits.map((e) => {
      const box = new THREE.Box3();
      for (const c of e.children) if (c.isMesh && c.name.startsWith('Pedestal')) box.setFromObject(c);
      return { x0: box.min.x - RADIUS, x1: box.max.x + RADIUS, z0: box.min.z - RADIUS, z1: box.max.z + RADIUS };
    });
  }

  free(x, z) {
    if (Math.abs(x) > this.xmax || Math.abs(z) > this.zmax) return false;
    return !this.boxes.some((b) => x > b.x0 && x < b.x1 && z > b.z0 && z < b.z1);
  }

  // Moves from p by (dx, dz) as far as the obstacles let it, sliding along
  // them (each axis on its own).
  move(p, dx, dz) {
    if (this.free(p.x + dx, p.z)) p.x += dx;
    if (this.free(p.x, p.z + dz)) p.z += dz;
  }
}
