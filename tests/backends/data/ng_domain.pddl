; A small no-gravity (NG) domain in the paper's style, for backend tests only.
(define (domain arti-ng-test)
  (:requirements :typing :fluents :negative-preconditions :time)
  (:types link plane)
  (:predicates (connected ?l1 - link ?l2 - link) (affects ?l1 - link ?l2 - link)
               (in-use) (free-to-move ?l - link) (increasing ?l - link ?x - plane)
               (decreasing ?l - link ?x - plane))
  (:functions (angle ?l - link ?x - plane) (speed-i) (speed-d))
  (:action start-increase
    :parameters (?l1 - link ?l2 - link ?x - plane)
    :precondition (and (connected ?l1 ?l2) (not (in-use)))
    :effect (and (in-use) (not (free-to-move ?l1)) (not (free-to-move ?l2)) (increasing ?l2 ?x)))
  (:action stop-increase
    :parameters (?l1 - link ?l2 - link ?x - plane)
    :precondition (and (connected ?l1 ?l2) (increasing ?l2 ?x))
    :effect (and (not (in-use)) (free-to-move ?l1) (free-to-move ?l2) (not (increasing ?l2 ?x))))
  (:action start-decrease
    :parameters (?l1 - link ?l2 - link ?x - plane)
    :precondition (and (connected ?l1 ?l2) (not (in-use)))
    :effect (and (in-use) (not (free-to-move ?l1)) (not (free-to-move ?l2)) (decreasing ?l2 ?x)))
  (:action stop-decrease
    :parameters (?l1 - link ?l2 - link ?x - plane)
    :precondition (and (connected ?l1 ?l2) (decreasing ?l2 ?x))
    :effect (and (not (in-use)) (free-to-move ?l1) (free-to-move ?l2) (not (decreasing ?l2 ?x))))
  (:action observe :parameters () :precondition (and) :effect (and))
  (:process move-increase
    :parameters (?l - link ?x - plane)
    :precondition (increasing ?l ?x)
    :effect (increase (angle ?l ?x) (* #t (speed-i))))
  (:process propagate-increase
    :parameters (?l1 - link ?l2 - link ?x - plane)
    :precondition (and (increasing ?l1 ?x) (affects ?l1 ?l2))
    :effect (increase (angle ?l2 ?x) (* #t (speed-i))))
  (:process move-decrease
    :parameters (?l - link ?x - plane)
    :precondition (decreasing ?l ?x)
    :effect (decrease (angle ?l ?x) (* #t (speed-d))))
  (:process propagate-decrease
    :parameters (?l1 - link ?l2 - link ?x - plane)
    :precondition (and (decreasing ?l1 ?x) (affects ?l1 ?l2))
    :effect (decrease (angle ?l2 ?x) (* #t (speed-d))))
  (:event back-to-zero
    :parameters (?l - link ?x - plane)
    :precondition (>= (angle ?l ?x) 360)
    :effect (and (assign (angle ?l ?x) 0.5)))
  (:event back-to-360
    :parameters (?l - link ?x - plane)
    :precondition (< (angle ?l ?x) 0)
    :effect (and (assign (angle ?l ?x) 359.5)))
)
