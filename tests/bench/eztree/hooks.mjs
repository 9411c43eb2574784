// Node ESM loader hooks so ez-tree's *unmodified* Vite-style source runs in Node:
//  1. resolve: relative imports without an extension ('./rng', './presets/index')
//     are retried with '.js' appended (Vite/bundler resolution).
//  2. load: '*.json' files (preset imports without `with {type:'json'}`) are served
//     as an ES module `export default <parsed JSON>`.
import { readFile } from 'node:fs/promises';
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

export async function resolve(specifier, context, next) {
  if ((specifier.startsWith('./') || specifier.startsWith('../')) &&
      !/\.[cm]?js$|\.json$/.test(specifier) && context.parentURL) {
    const url = new URL(specifier + '.js', context.parentURL);
    if (existsSync(fileURLToPath(url))) return next(specifier + '.js', context);
  }
  return next(specifier, context);
}

export async function load(url, context, next) {
  if (url.startsWith('file:') && url.endsWith('.json')) {
    const text = await readFile(fileURLToPath(url), 'utf8');
    JSON.parse(text); // validate
    return { format: 'module', source: `export default ${text};`, shortCircuit: true };
  }
  return next(url, context);
}
