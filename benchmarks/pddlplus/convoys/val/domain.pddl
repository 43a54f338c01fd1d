(define (domain convoys-val)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types convoy location)
  (:predicates (at ?c - convoy ?l - location) (road ?a - location ?b - location)
               (idle ?c - convoy) (moving ?c - convoy ?a - location ?b - location) (operating))
  (:functions (speed ?c - convoy) (traffic ?a - location ?b - location)
              (length ?a - location ?b - location) (progress ?c - convoy) (clock) (deadline))
  (:process time-passes
    :parameters ()
    :precondition (and (operating))
    :effect (and (increase (clock) (* #t 1))))
  (:action depart
    :parameters (?c - convoy ?a - location ?b - location)
    :precondition (and (at ?c ?a) (idle ?c) (road ?a ?b))
    :effect (and (not (at ?c ?a)) (not (idle ?c)) (moving ?c ?a ?b) (assign (progress ?c) 0)
                 (increase (traffic ?a ?b) 1) (increase (traffic ?b ?a) 1)))
  ;; VAL twin: traffic^2 as a product
  (:process drive
    :parameters (?c - convoy ?a - location ?b - location)
    :precondition (and (moving ?c ?a ?b))
    :effect (and (increase (progress ?c) (* #t (/ (speed ?c) (* (traffic ?a ?b) (traffic ?a ?b)))))))
  (:action arrive
    :parameters (?c - convoy ?a - location ?b - location)
    :precondition (and (moving ?c ?a ?b) (>= (progress ?c) (length ?a ?b))
                       (<= (clock) (deadline)))
    :effect (and (not (moving ?c ?a ?b)) (at ?c ?b) (idle ?c)
                 (decrease (traffic ?a ?b) 1) (decrease (traffic ?b ?a) 1)))
)
