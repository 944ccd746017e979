// Predict, then reveal: the page's quiz. With "quiz me" ticked, a click on a pixel asks
// the student what the algorithm decides there before showing it, one decision at a
// time, and checks each answer against what the algorithm's own loops recorded when it
// ran (hsr why's --json, from the module): never a second implementation that could
// disagree with the algorithm.
//
// The questions, built from that answer:
//   - first, which triangle the pixel will show (at a certified tie, where the exact
//     reference finds two or more triangles exactly nearest, any of them is right);
//   - then, event by event in the order the loop met them, with the numbers the loop
//     decided by: for an event about a triangle, whether the pixel shows that triangle
//     after it (the depth test, a span's rule, a resolve), or for the painter, which
//     paints them all, which piece it paints next; for an
//     event about something else (Warnock's window, a BVH node, a culling stage), which
//     decision the loop made there, among all the algorithm declares (Warnock's rules) or
//     else those made at this pixel;
//   - for a line drawing, along the edge nearest the pixel (hsr why --edge X,Y): Appel's,
//     at each crossing of a contour, how the edge's quantitative invisibility changes;
//     Roberts', what the test of each body decided (hides part of it, none, ruled out);
//     the floating horizon's, where the segment lies against the horizons at its start
//     and at each column center.
// At most kStepQuestions events are asked about (those about triangles first, then the
// last of the others); the rest are revealed as the quiz passes them. At the end, the whole answer, as hsr why prints it.
"use strict";

const kStepQuestions = 8;

// "lost the depth test: farther than ..." -> "lost the depth test": a decision without the
// reasons that follow it, so that one choice does not give the next away.
const decisionOf = (outcome) => outcome.split(": ")[0];
// "6 polygons meet it (...); more than one meets it and none surrounds it" -> its numbers,
// without the conclusion drawn from them after the semicolon: what the student decides from.
const numbersOf = (detail) => detail.split("; ")[0];
// A triangle with its distance along the view axis where the loop met it, when it has one.
const withDistance = (name, distance) => (Number.isFinite(distance) ? `${name}, ${distance.toPrecision(6)} away` : name);

// The choices of a question: each a label and whether it is right; in the order given,
// without repeats.
function choicesOf(labels, isRight) {
  return [...new Set(labels)].map((label) => ({ label, right: isRight(label) }));
}

// A pixel's quiz, from hsr why's answer for one pixel of a surface algorithm, whose
// decisions about what is not a triangle are `declared` (all of Warnock's rules), and
// which `paintsInOrder` (the painter: every piece reaching the pixel is painted, and
// what it decides is the order).
function pixelQuiz(pixel, declared, paintsInOrder) {
  const history = pixel.history;
  const named = history.filter((event) => event.triangle !== null).map((event) => event.name);
  const tied = pixel.reference.ambiguous ? pixel.reference.tied.map((t) => t.name) : [];
  const rightTriangle = (name) => name === pixel.shows.name || tied.includes(name);
  // Each triangle's distance where the loop first met it here (a choice's label shows it).
  const distances = new Map();
  for (const event of history) if (event.triangle !== null && !distances.has(event.name)) distances.set(event.name, event.distance);
  const names = [...new Set([...named, ...tied, pixel.reference.name, "the background"])];
  const first = {
    prompt: `Which triangle will pixel (${pixel.x}, ${pixel.y}) show?`,
    context: `The algorithm met ${history.length} ${history.length === 1 ? "event" : "events"} here; the triangles among them are the choices, ` +
             "each with its distance along the view axis where it was met.",
    choices: names.map((name) => ({ label: withDistance(name, distances.get(name)), right: rightTriangle(name) })),
    answer: `It shows ${pixel.shows.name}` +
            (tied.length ? `: a certified tie of ${tied.join(" and ")}, exactly nearest, so any of them is right.`
                         : pixel.agrees ? ", as the exact reference does." : `; the exact reference shows ${pixel.reference.name}.`),
  };
  // The decisions made here about things that are not triangles (windows, nodes, stages).
  const otherDecisions = history.filter((event) => event.triangle === null).map((event) => decisionOf(event.outcome));
  // The events about triangles first, then the others from the last back (the last
  // window, node or stage is the one that decided), kStepQuestions of them in the loop's order.
  const aboutTriangles = history.flatMap((event, index) => (event.triangle !== null ? [index] : []));
  const aboutOthers = declared.length > 1 || new Set(otherDecisions).size > 1 ? history.flatMap((event, index) => (event.triangle === null ? [index] : [])).reverse() : [];
  const asked = [...aboutTriangles, ...aboutOthers].slice(0, kStepQuestions).sort((a, b) => a - b);
  // The painter's question: which of the pieces still to come it paints next. A choice
  // names the piece's triangle, its distance here and whether it is whole or cut (not its
  // place in the order, which the detail begins with).
  const pieceOf = (event) => `${withDistance(event.name, event.distance)} (${/\(([^()]*)\)$/.exec(event.detail)?.[1] ?? "a piece"})`;
  // The pieces are the events about triangles (culling stages' events may come first).
  const pieces = aboutTriangles.map((index) => history[index]);
  const nextPiece = (index) => {
    const painted = aboutTriangles.indexOf(index);
    return {
      event: index,
      prompt: `Event ${index + 1}: which piece does the painter paint ${painted === 0 ? "first" : "next"} at this pixel?`,
      context: `${pieces.length} pieces reach pixel (${pixel.x}, ${pixel.y}); the painter paints every one, back to front, ` +
               `each over the ones before. ${painted} painted so far.`,
      choices: choicesOf(pieces.slice(painted).map(pieceOf).sort(), (label) => label === pieceOf(history[index])),
      answer: `${history[index].name}: ${history[index].detail}.`,
    };
  };
  // The painter's last piece is forced: not asked.
  const steps = asked.filter((index) => !paintsInOrder || index !== aboutTriangles[aboutTriangles.length - 1]).map((index) => {
    const event = history[index];
    const at = `Event ${index + 1} of ${history.length}: ${event.name}. ${numbersOf(event.detail)}.`;
    if (paintsInOrder && event.triangle !== null) return nextPiece(index);
    if (event.triangle !== null) {
      return {
        event: index,
        prompt: `After event ${index + 1}, does the pixel show ${event.name}?`,
        context: at,
        choices: [{ label: "yes", right: event.shown }, { label: "no", right: !event.shown }],
        answer: `${event.shown ? "Yes" : "No"}: ${event.outcome}.`,
      };
    }
    // Every decision the algorithm can take there when it declares them, else those it
    // took at this pixel (at most four).
    const decision = decisionOf(event.outcome);
    const offered = declared.includes(decision) ? declared : [decision, ...otherDecisions.filter((other) => other !== decision)].slice(0, 4).sort();
    return {
      event: index,
      prompt: `What does the loop decide at event ${index + 1}?`,
      context: at,
      choices: choicesOf(offered, (label) => label === decision),
      answer: `${event.outcome}.`,
    };
  });
  // A pixel where nothing was met offers one choice: nothing to predict there.
  return { events: history.map((event) => `${event.name}: ${event.outcome}`), questions: [...(first.choices.length > 1 ? [first] : []), ...steps] };
}

// An edge's quiz, from hsr why --edge's answer: Appel's, how the edge's quantitative
// invisibility changes at each crossing the walk met; Roberts', what the test of each
// body decided; the floating horizon's, where the segment lies against the horizons at
// its start and each column center (the algorithm's declared decisions are offered).
function edgeQuiz(edge) {
  const change = (value) => (value > 0 ? `+${value}: it passes behind` : `${value}: it comes out from behind`);
  const of = (index) => `Event ${index + 1} of ${edge.walk.length} along ${edge.name}`;
  const question = (event, index) => {
    if (event.change !== 0 && event.subject === "") {  // a change of Appel's QI
      return {
        event: index,
        prompt: `At u = ${event.u.toPrecision(4)} the walk crosses a contour's projection. How does the edge's QI change?`,
        context: `${of(index)}. ${event.detail}.`,
        choices: choicesOf([change(1), change(-1), change(event.change)].sort(), (label) => label === change(event.change)),
        answer: `${event.outcome}.`,
      };
    }
    const decision = decisionOf(event.outcome);
    if (!edge.decisions.includes(decision)) return null;
    // The numbers it decided by, without the conclusion after the semicolon (a detail
    // without one would give the answer away: it comes with the answer).
    return {
      event: index,
      // Not where along the edge (Roberts records one only where a body hides a part).
      prompt: event.subject ? `${event.subject}: what does the algorithm decide there?` : "What does the algorithm decide for this edge?",
      context: `${of(index)}${event.subject ? `: ${event.subject}` : ""}. ` +
               (event.detail.includes("; ") ? `${numbersOf(event.detail)}.` : "Look at the drawing: where does it lie, against the edge?"),
      choices: choicesOf(edge.decisions, (label) => label === decision),
      answer: `${event.outcome}: ${event.detail}.`,
    };
  };
  const steps = edge.walk.map(question).filter((asked) => asked !== null).slice(0, kStepQuestions);
  const place = (event) => (Number.isFinite(event.u) ? `at u = ${event.u.toPrecision(4)}: ` : "");
  return { events: edge.walk.map((event) => `${place(event)}${event.subject ? `${event.subject}: ` : ""}${event.outcome}`), questions: steps };
}

// The quiz in progress: its questions, the one shown, the answers right so far, and
// whether the algorithm agrees with the reference there (shown only at the end).
const quiz = { questions: [], events: [], current: 0, right: 0, answered: false, verdict: "", at: null };

// The events the quiz has passed: every one before the question shown, each with what
// the loop decided (what is asked stays hidden until answered).
function showPassedEvents(upTo) {
  const passed = quiz.events.slice(0, upTo);
  $("quizEvents").replaceChildren(...passed.map((text, i) => element("li", { textContent: `${i + 1}. ${asTheStudentNamesIt(text)}` })));
}

function showQuestion() {
  quiz.answered = false;
  const question = quiz.questions[quiz.current];
  showPassedEvents(question.event ?? 0);
  $("quizProgress").textContent = `question ${quiz.current + 1} of ${quiz.questions.length}`;
  $("quizContext").textContent = asTheStudentNamesIt(question.context);
  $("quizQuestion").textContent = asTheStudentNamesIt(question.prompt);
  $("quizChoices").replaceChildren(...question.choices.map((choice) => {
    const button = element("button", { type: "button", textContent: asTheStudentNamesIt(choice.label) });
    button.addEventListener("click", () => answer(choice, button));
    return button;
  }));
  $("quizFeedback").textContent = "";
  $("quizFeedback").className = "";
  $("quizNext").hidden = true;
}

// Checks a choice against what the algorithm did, says so, and offers the next question.
function answer(choice, button) {
  if (quiz.answered) return;
  quiz.answered = true;
  quiz.right += choice.right;
  for (const other of $("quizChoices").children) other.disabled = true;
  button.classList.add("chosen");
  const question = quiz.questions[quiz.current];
  $("quizFeedback").textContent = `${choice.right ? "Right." : "Not quite."} ${asTheStudentNamesIt(question.answer)}`;
  $("quizFeedback").className = choice.right ? "right" : "wrong";
  $("quizNext").textContent = quiz.current + 1 < quiz.questions.length ? "next question" : "see the whole answer";
  $("quizNext").hidden = false;
  $("quizNext").focus();
}

function nextQuestion() {
  if (++quiz.current < quiz.questions.length) return showQuestion();
  $("quizProgress").textContent = `${quiz.right} of ${quiz.questions.length} predicted right; the whole answer:`;
  for (const part of ["quizEvents", "quizContext", "quizQuestion", "quizChoices", "quizFeedback"]) $(part).replaceChildren();
  $("quizNext").hidden = true;
  $("why").hidden = false;
  $("whyBox").className = quiz.verdict;
}

// Starts the quiz on the module's answer to why (a pixel's, or an edge's) for the pixel
// clicked, `at` ([x, y]); an answer with nothing to ask is shown at once.
function startQuiz(result, at) {
  const built = result.edge ? edgeQuiz(result.edge)
                            : pixelQuiz(result.answer.pixels[0], result.answer.decisions, result.answer.paints_in_order);
  Object.assign(quiz, built, { current: 0, right: 0, verdict: $("whyBox").className, at });
  $("quiz").hidden = false;
  $("why").hidden = quiz.questions.length > 0;
  if (quiz.questions.length === 0) {
    for (const part of ["quizEvents", "quizContext", "quizQuestion", "quizChoices", "quizFeedback"]) $(part).replaceChildren();
    $("quizNext").hidden = true;
    $("quizProgress").textContent = "Nothing to predict here: the algorithm met at most one thing at this pixel. Its answer:";
    return;
  }
  $("whyBox").className = "";  // agreeing or not is for the end
  showQuestion();
}

// Whether a quiz is under way at pixel (x, y): a second click there (a double click's)
// leaves it as it is.
const quizUnderWayAt = (x, y) => !$("quiz").hidden && quiz.current < quiz.questions.length && quiz.at?.[0] === x && quiz.at?.[1] === y;

function stopQuiz() {
  $("quiz").hidden = true;
  $("why").hidden = false;
}

$("quizNext").addEventListener("click", nextQuestion);
