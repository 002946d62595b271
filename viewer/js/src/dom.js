// The overlay's one DOM helper, shared by every panel (overlay.js, loads.js,
// deflection.js, efforts.js).

// A new element `tag` with inline `style` and, when given, its text.
export function el(tag, style, text) {
  const e = document.createElement(tag);
  Object.assign(e.style, style);
  if (text !== undefined) e.textContent = text;
  return e;
}
