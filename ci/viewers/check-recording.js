#!/usr/bin/env node
// Checks a sightline recording against the viewers' own artefacts, from the
// channels and messages a reader dumped as JSON lines (tests/e2e/viewers.rs
// writes them with the official Python MCAP reader):
//
//   {"schema": NAME, "encoding": E, "data": SCHEMA-TEXT}      one per schema
//   {"topic": T, "schema": NAME, "encoding": E, "data": MESSAGE-TEXT}  one per message
//
// 1. every `foxglove.*` schema equals the one npm `@foxglove/schemas` publishes
//    (its `jsonschema` export, pinned in package.json);
// 2. every schema is in the subset Foxglove's and Lichtblick's `parseJsonSchema`
//    (packages/mcap-support/src/parseJsonSchema.ts) accepts: an object with
//    `properties`, each property typed `boolean`, `string` (contentEncoding
//    absent or base64), `number`, `integer`, `object` (the same, recursively) or
//    `array` of one of those but an array, or a `oneOf` of numeric `const`s;
// 3. every message validates against its channel's schema with ajv.
//
// Usage: node check-recording.js DUMP.jsonl. Prints one line per problem and a
// summary; exits 1 when there is a problem, 2 on bad usage.
"use strict";

const fs = require("fs");
const { isDeepStrictEqual } = require("util");
const Ajv = require("ajv");
const official = require("@foxglove/schemas/jsonschema");

const path = process.argv[2];
if (!path) {
  console.error("usage: node check-recording.js DUMP.jsonl");
  process.exit(2);
}

const schemas = new Map();
const messages = [];
for (const line of fs.readFileSync(path, "utf8").split("\n")) {
  if (line.trim() === "") continue;
  const record = JSON.parse(line);
  if (record.topic === undefined) schemas.set(record.schema, record);
  else messages.push(record);
}

const problems = [];

// The rules of parseJsonSchema: what it reads, and what makes it throw.
function subsetProblems(schema, where) {
  const found = [];
  if (schema.type !== "object") {
    found.push(`${where}: "type" is ${JSON.stringify(schema.type)}, not "object"`);
    return found;
  }
  if (schema.properties === null || typeof schema.properties !== "object") {
    found.push(`${where}: an object without "properties"`);
    return found;
  }
  for (const [name, field] of Object.entries(schema.properties)) {
    const at = `${where}.${name}`;
    if (Array.isArray(field.oneOf)) {
      if (!field.oneOf.every((alternative) => typeof alternative.const === "number")) {
        found.push(`${at}: a oneOf whose alternatives are not all numeric constants`);
      }
      continue;
    }
    switch (field.type) {
      case "boolean":
      case "number":
      case "integer":
        break;
      case "string":
        if (field.contentEncoding !== undefined && field.contentEncoding !== "base64") {
          found.push(`${at}: contentEncoding ${JSON.stringify(field.contentEncoding)}`);
        }
        break;
      case "object":
        found.push(...subsetProblems(field, at));
        break;
      case "array": {
        const items = field.items ?? {};
        if (items.type === "object") found.push(...subsetProblems(items, `${at}[]`));
        else if (items.type === "string" && items.contentEncoding !== undefined) {
          found.push(`${at}[]: contentEncoding on an array item`);
        } else if (!["boolean", "string", "number", "integer"].includes(items.type)) {
          found.push(`${at}[]: item type ${JSON.stringify(items.type)}`);
        }
        break;
      }
      default:
        found.push(`${at}: type ${JSON.stringify(field.type)}`);
    }
  }
  return found;
}

const ajv = new Ajv({ allErrors: true, strict: false });
const validators = new Map();
for (const [name, record] of schemas) {
  if (record.encoding !== "jsonschema") {
    problems.push(`schema ${name}: encoding ${JSON.stringify(record.encoding)}, not jsonschema`);
    continue;
  }
  const schema = JSON.parse(record.data);
  if (name.startsWith("foxglove.")) {
    const published = official[name.slice("foxglove.".length)];
    if (published === undefined) {
      problems.push(`schema ${name}: @foxglove/schemas publishes no such schema`);
    } else if (!isDeepStrictEqual(schema, published)) {
      problems.push(`schema ${name}: differs from the one @foxglove/schemas publishes`);
    }
  }
  for (const problem of subsetProblems(schema, name)) problems.push(`schema ${problem}`);
  validators.set(name, ajv.compile(schema));
}

const counts = new Map();
for (const message of messages) {
  counts.set(message.topic, (counts.get(message.topic) ?? 0) + 1);
  const validate = validators.get(message.schema);
  if (message.encoding !== "json") {
    problems.push(`${message.topic}: message encoding ${JSON.stringify(message.encoding)}, not json`);
  } else if (validate === undefined) {
    problems.push(`${message.topic}: no schema ${message.schema}`);
  } else if (!validate(JSON.parse(message.data))) {
    const first = validate.errors[0];
    problems.push(`${message.topic}: ${first.instancePath || "/"} ${first.message} (${message.schema})`);
  }
}

// One line per kind of problem and topic, not one per message.
const distinct = [...new Set(problems)];
for (const problem of distinct) console.log(problem);
console.log(
  `${schemas.size} schemas, ${messages.length} messages on ${counts.size} topics: ` +
    `${problems.length} problem(s)`,
);
process.exit(problems.length === 0 ? 0 : 1);
