// The page's data: the JSON that `argil view` embeds in the page
// (format argil.view, version 1; docs/view.md), with its binary arrays
// decoded from base64 into typed arrays.

function bytes(base64) {
  const text = atob(base64);
  const out = new Uint8Array(text.length);
  for (let i = 0; i < text.length; ++i) out[i] = text.charCodeAt(i);
  return out;
}

// Typed views of little-endian arrays; a fresh buffer is always aligned.
export const float32 = (b64) => new Float32Array(bytes(b64).buffer);
export const float64 = (b64) => new Float64Array(bytes(b64).buffer);
export const uint32 = (b64) => new Uint32Array(bytes(b64).buffer);
export const uint8 = (b64) => bytes(b64);

/// Reads the embedded data and decodes every array once.
export function loadViewData(element) {
  const data = JSON.parse(element.textContent);
  if (data.format !== "argil.view" || data.version !== 1) {
    throw new Error(`not argil.view version 1 data: ${data.format} ${data.version}`);
  }
  for (const face of data.faces) {
    face.positions = float32(face.positions);
    face.normals = float32(face.normals);
    face.uv = float64(face.uv);
    face.indices = uint32(face.indices);
  }
  for (const frame of data.frames) {
    for (const key of Object.keys(frame.faces)) frame.faces[key] = float32(frame.faces[key]);
    frame.contacts = float32(frame.contacts);
  }
  const run = data.run;
  if (run) {
    run.time = float64(run.time);
    run.device = float32(run.device);
    run.proxy = float32(run.proxy);
    run.orientation = float32(run.orientation);
    run.engaged = uint8(run.engaged);
    run.force = float32(run.force);
    run.tool = uint8(run.tool);
  }
  for (const tool of data.tools) {
    if (!tool.mesh) continue;
    tool.mesh.positions = float32(tool.mesh.positions);
    tool.mesh.normals = float32(tool.mesh.normals);
    tool.mesh.indices = uint32(tool.mesh.indices);
  }
  return data;
}
