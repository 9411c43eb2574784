// Registers hooks.mjs before bench.mjs loads ez-tree: node --import ./register.mjs bench.mjs
import { register } from 'node:module';
register('./hooks.mjs', import.meta.url);
