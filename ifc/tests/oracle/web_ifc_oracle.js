// The independent reader for the import's oracle test (ifc/tests/oracle/web_ifc_oracle.py): npm's
// web-ifc (pinned in ci/oracles/package.json, installed by ci/install-deps) reads an IFC model
// and prints, as JSON, each building storey with the walls, curtain walls, doors, windows and
// spaces it holds (by GlobalId) and each such element's axis-aligned bounding box in the model's
// own coordinates (IFC's z up, metres).
//
// usage: node web_ifc_oracle.js MODEL.ifc NODE_MODULES_DIR
'use strict';
const fs = require('fs');
const path = require('path');

async function main() {
  const [model, modules] = process.argv.slice(2);
  const WebIFC = require(path.join(path.resolve(modules), 'web-ifc'));
  const api = new WebIFC.IfcAPI();
  await api.Init();
  const id = api.OpenModel(new Uint8Array(fs.readFileSync(model)));

  const kinds = new Map([
    [WebIFC.IFCWALL, 'wall'], [WebIFC.IFCWALLSTANDARDCASE, 'wall'],
    [WebIFC.IFCCURTAINWALL, 'curtain wall'], [WebIFC.IFCDOOR, 'door'],
    [WebIFC.IFCWINDOW, 'window'], [WebIFC.IFCSPACE, 'space'],
  ]);
  const ids = (type) => {
    const v = api.GetLineIDsWithType(id, type);
    const out = [];
    for (let i = 0; i < v.size(); i++) out.push(v.get(i));
    return out;
  };
  const text = (attribute) => (attribute && attribute.value !== undefined ? String(attribute.value) : '');

  // Storeys and what they hold: contained elements, and spaces aggregated under them.
  const storeys = new Map();
  for (const sid of ids(WebIFC.IFCBUILDINGSTOREY)) {
    const line = api.GetLine(id, sid);
    storeys.set(sid, {name: text(line.Name), global_id: text(line.GlobalId), elements: []});
  }
  const addTo = (storey, eid) => {
    const kind = kinds.get(api.GetLineType(id, eid));
    if (!kind) return;
    storey.elements.push({express_id: eid, kind});
  };
  for (const rid of ids(WebIFC.IFCRELCONTAINEDINSPATIALSTRUCTURE)) {
    const rel = api.GetLine(id, rid);
    const storey = storeys.get(rel.RelatingStructure.value);
    if (storey) for (const e of rel.RelatedElements) addTo(storey, e.value);
  }
  for (const rid of ids(WebIFC.IFCRELAGGREGATES)) {
    const rel = api.GetLine(id, rid);
    const storey = storeys.get(rel.RelatingObject.value);
    if (storey) for (const e of rel.RelatedObjects) addTo(storey, e.value);
  }

  // Bounding boxes: web-ifc's meshes are y-up (three.js): IFC's (x, y, z) is its (x, -z, y).
  const boxOf = (eid) => {
    const mesh = api.GetFlatMesh(id, eid);
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let g = 0; g < mesh.geometries.size(); g++) {
      const placed = mesh.geometries.get(g);
      const geometry = api.GetGeometry(id, placed.geometryExpressID);
      const v = api.GetVertexArray(geometry.GetVertexData(), geometry.GetVertexDataSize());
      const m = placed.flatTransformation;
      for (let i = 0; i < v.length; i += 6) {
        const x = v[i], y = v[i + 1], z = v[i + 2];
        const wx = m[0] * x + m[4] * y + m[8] * z + m[12];
        const wy = m[1] * x + m[5] * y + m[9] * z + m[13];
        const wz = m[2] * x + m[6] * y + m[10] * z + m[14];
        const p = [wx, -wz, wy];
        for (let k = 0; k < 3; k++) {
          lo[k] = Math.min(lo[k], p[k]);
          hi[k] = Math.max(hi[k], p[k]);
        }
      }
      geometry.delete();
    }
    return lo[0] <= hi[0] ? {min: lo, max: hi} : null;
  };

  const out = {storeys: []};
  for (const storey of storeys.values()) {
    const elements = storey.elements.map(({express_id, kind}) => ({
      global_id: text(api.GetLine(id, express_id).GlobalId),
      name: text(api.GetLine(id, express_id).Name),
      kind,
      box: boxOf(express_id),
    }));
    out.storeys.push({name: storey.name, global_id: storey.global_id, elements});
  }
  api.CloseModel(id);
  process.stdout.write(JSON.stringify(out) + '\n');
}

main().catch((e) => {
  process.stderr.write(`web_ifc_oracle: ${e.stack || e}\n`);
  process.exit(1);
});
