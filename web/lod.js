// Levels of detail: museum.glb keeps each vessel's levels as sibling meshes
// under its "Vessel: T" node, each with extras.lod_distance (glTF has no core
// LOD). They become one THREE.LOD, which shows the level for the camera's
// distance to the vessel every frame.
import * as THREE from 'three';

function triangles(mesh) {
  const g = mesh.geometry;
  return (g.index ? g.index.count : g.attributes.position.count) / 3;
}

// Replaces every vessel node by a THREE.LOD; returns the LOD objects and the
// triangle count of the whole museum with every vessel at its finest level.
export function makeLods(root) {
  const nodes = [];
  root.traverse((o) => { if (o.userData && Array.isArray(o.userData.lod)) nodes.push(o); });
  let full = 0;
  root.traverse((o) => { if (o.isMesh && o.userData.lod_distance === undefined) full += triangles(o); });
  const vessels = nodes.map((node) => {
    const lod = new THREE.LOD();
    lod.name = node.name;
    lod.userData = node.userData;
    lod.position.copy(node.position);
    lod.quaternion.copy(node.quaternion);
    lod.scale.copy(node.scale);
    const levels = node.children.filter((c) => c.userData.lod_distance !== undefined)
      .sort((a, b) => a.userData.lod_distance - b.userData.lod_distance);
    // Each level keeps its node's translation and scale: they turn its
    // quantized positions back into metres (KHR_mesh_quantization).
    levels.forEach((mesh, k) => {
      if (k === 0) full += triangles(mesh);
      lod.addLevel(mesh, mesh.userData.lod_distance);
    });
    node.parent.add(lod);
    node.parent.remove(node);
    return lod;
  });
  return { vessels, fullDetailTriangles: full };
}
