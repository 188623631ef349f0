// WebXR locomotion: each controller casts a ray; releasing the trigger on
// the floor teleports the visitor there (when the spot is free), on an
// exhibit shows its label. The visitor's rig (the camera's parent) is what
// moves, so the headset's own tracking stays relative to it.
import * as THREE from 'three';

export class XrLocomotion {
  constructor(renderer, rig, scene, obstacles, pickables, onPick) {
    this.renderer = renderer;
    this.rig = rig;
    this.obstacles = obstacles;
    this.pickables = pickables;
    this.onPick = onPick;
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

  update() {
    this.marker.visible = false;
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
