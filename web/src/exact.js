// Exact numbers on the pages: each exact rational ("p/q" or an integer, as
// minksum prints them) shown with its decimal value beside it, the exact
// text folded behind a click when it is long.  The decimal is computed from
// the exact text with BigInt (correctly rounded to DIGITS significant
// digits, half away from zero), so a 100-digit fraction, or one whose
// numerator and denominator both exceed the double range, gets its true
// value, not NaN.

const DIGITS = 12;
// Exact texts longer than this are folded (a <details> element): the
// decimal shows, the fraction opens with a click.
export const FOLD_LENGTH = 40;

const pow10 = (k) => 10n ** BigInt(k);

// The decimal value of an exact rational text: { text, exact } where exact
// says the decimal is the value itself (1/4 = 0.25), not its rounding.
export function decimalOf(rational) {
  const [ps, qs = '1'] = String(rational).trim().split('/');
  let p = BigInt(ps);
  const q = BigInt(qs);
  if (q <= 0n) throw new Error(`not an exact rational: ${rational}`);
  const negative = p < 0n;
  if (negative) p = -p;
  if (p === 0n) return { text: '0', exact: true };
  // e = floor(log10(p / q)): 10^e <= p/q < 10^(e+1).
  const atLeast = (k) => (k >= 0 ? p >= q * pow10(k) : p * pow10(-k) >= q);
  let e = p.toString().length - q.toString().length;
  while (!atLeast(e)) --e;
  while (atLeast(e + 1)) ++e;
  // m = round(p/q * 10^(DIGITS-1-e)), DIGITS digits.
  const shift = DIGITS - 1 - e;
  const num = shift >= 0 ? p * pow10(shift) : p;
  const den = shift >= 0 ? q : q * pow10(-shift);
  let m = (2n * num + den) / (2n * den);
  const exact = num % den === 0n;
  if (m >= pow10(DIGITS)) { m /= 10n; ++e; }
  let digits = m.toString().replace(/0+$/, '') || '0';
  let text;
  if (e >= -6 && e < 21) {
    if (e >= 0) {
      const int = digits.length > e + 1 ? digits.slice(0, e + 1) : digits.padEnd(e + 1, '0');
      const frac = digits.length > e + 1 ? digits.slice(e + 1) : '';
      text = frac ? `${int}.${frac}` : int;
    } else {
      text = `0.${'0'.repeat(-e - 1)}${digits}`;
    }
  } else {
    text = (digits.length > 1 ? `${digits[0]}.${digits.slice(1)}` : digits) + `e${e}`;
  }
  return { text: (negative ? '-' : '') + text, exact };
}

// "≈ 58.6666666667" or "= 0.25"; '' for a short integer (its own decimal).
export function decimalText(rational) {
  const t = String(rational);
  if (!t.includes('/') && t.replace('-', '').length <= 15) return '';
  const d = decimalOf(t);
  return (d.exact ? '= ' : '≈ ') + d.text;
}

// The decimals of several exact rationals (a point "x y z"): "≈ (x, y, z)",
// '' when each is a short integer.
export function decimalsText(rationals) {
  if (rationals.every((r) => decimalText(r) === '')) return '';
  const ds = rationals.map((r) => decimalOf(r));
  return (ds.every((d) => d.exact) ? '= (' : '≈ (') + ds.map((d) => d.text).join(', ') + ')';
}

// One exact value on a page: the element `exactElement` (holding the exact
// text, with the caller's id and data attributes, as before), its decimal
// beside it (class "decimal"), and, when the exact text is long, the exact
// element inside a <details> whose summary says how long it is.
export function exactWithDecimal(el, exactElement, decimal) {
  const text = exactElement.textContent;
  const parts = [];
  if (decimal) parts.push(el('div', { class: 'decimal', text: decimal }));
  if (text.length > FOLD_LENGTH) {
    parts.push(el('details', { class: 'fold' },
      el('summary', { text: `exact value (${text.length} characters)` }), exactElement));
  } else {
    parts.push(exactElement);
  }
  return el('div', { class: 'value' }, ...parts);
}
