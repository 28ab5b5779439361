// What an observer has been sent, rebuilt from keyframes and deltas (the same rules as a gRPC
// Observe subscriber's; see proto/kerf/v1/frame.proto): the view's vertices in increasing id
// order with their positions (or forces), its elements by id, and the counts a viewer shows.

function floats(bytes) {
  // Packed little-endian float32; a view needs 4-byte alignment, so copy when unaligned.
  if (bytes.byteOffset % 4 === 0) {
    return new Float32Array(bytes.buffer, bytes.byteOffset, bytes.byteLength / 4);
  }
  return new Float32Array(bytes.slice().buffer);
}

export class FrameView {
  constructor() {
    this.vertices = [];           // ids, increasing
    this.index = new Map();       // id -> position in vertices
    this.elements = new Map();    // id -> { vertices: [...], onCut }
    this.values = new Float32Array(0);  // x, y, z per vertex (positions or forces)
    this.sequence = 0;
    this.gaps = 0;
    this.frames = 0;
    this.started = false;
  }

  // Applies one decoded Frame. Returns false (and changes nothing) for a delta that does not
  // follow (the caller reconnects for a fresh keyframe).
  apply(frame) {
    const sequence = Number(frame.sequence);
    if (!frame.keyframe && !this.started) return false;
    if (frame.keyframe) {
      this.vertices = [];
      this.elements = new Map();
    } else if (sequence > this.sequence + 1) {
      this.gaps += sequence - this.sequence - 1;  // positions skipped (latest wins)
    }
    const removed = new Set(frame.removedVertices ?? []);
    if (removed.size > 0) this.vertices = this.vertices.filter((v) => !removed.has(v));
    const added = frame.addedVertices ?? [];
    if (added.length > 0) {
      this.vertices = this.vertices.concat(added);
      this.vertices.sort((a, b) => a - b);
    }
    if (removed.size > 0 || added.length > 0 || frame.keyframe) {
      this.index = new Map(this.vertices.map((id, i) => [id, i]));
    }
    for (const id of frame.removedElements ?? []) this.elements.delete(id);
    const ids = frame.addedElements ?? [];
    const corners = ids.length > 0 ? (frame.addedElementVertices.length / ids.length) : 0;
    const onCut = frame.addedElementsOnCut ?? new Uint8Array(0);
    ids.forEach((id, i) => {
      this.elements.set(id, {
        vertices: frame.addedElementVertices.slice(corners * i, corners * (i + 1)),
        onCut: onCut[i] === 1,
      });
    });
    const bytes = frame.positions?.length ? frame.positions : frame.nodalForces;
    if (bytes?.length) this.values = floats(bytes);
    this.sequence = sequence;
    this.started = true;
    this.frames += 1;
    return true;
  }

  // x, y, z of a vertex id (undefined if the view does not have it).
  value(id) {
    const i = this.index.get(id);
    return i === undefined ? undefined : this.values.subarray(3 * i, 3 * i + 3);
  }
}
